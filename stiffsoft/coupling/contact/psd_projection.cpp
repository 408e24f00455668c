#include <stiffsoft/coupling/contact/psd_projection.hpp>

#include <Eigen/Eigenvalues>

namespace stiffsoft::contact {

template <int N>
Eigen::Matrix<double, N, N> project_to_psd(const Eigen::Matrix<double, N, N>& A) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> es(A);
  const auto& lambda = es.eigenvalues();
  if (lambda.minCoeff() >= 0.0) return A;
  const auto& V = es.eigenvectors();
  return V * lambda.cwiseMax(0.0).asDiagonal() * V.transpose();
}

template Eigen::Matrix<double, 2, 2> project_to_psd<2>(const Eigen::Matrix<double, 2, 2>&);
template Eigen::Matrix<double, 3, 3> project_to_psd<3>(const Eigen::Matrix<double, 3, 3>&);
template Eigen::Matrix<double, 6, 6> project_to_psd<6>(const Eigen::Matrix<double, 6, 6>&);
template Eigen::Matrix<double, 9, 9> project_to_psd<9>(const Eigen::Matrix<double, 9, 9>&);
template Eigen::Matrix<double, 12, 12> project_to_psd<12>(const Eigen::Matrix<double, 12, 12>&);

void project_leading_block_to_psd(Eigen::Matrix<double, 12, 12>& H, int active_vertices) {
  switch (active_vertices) {
    case 1: H.topLeftCorner<3, 3>() = project_to_psd<3>(H.topLeftCorner<3, 3>()); break;
    case 2: H.topLeftCorner<6, 6>() = project_to_psd<6>(H.topLeftCorner<6, 6>()); break;
    case 3: H.topLeftCorner<9, 9>() = project_to_psd<9>(H.topLeftCorner<9, 9>()); break;
    default: H = project_to_psd<12>(H); break;
  }
}

}  // namespace stiffsoft::contact
