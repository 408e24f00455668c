#include <stiffsoft/coupling/contact/psd_projection.hpp>
#include <stiffsoft/coupling/contact/symmetric_eigen.hpp>

#include <Eigen/Eigenvalues>
#include <cmath>

namespace stiffsoft::contact {

template <int N>
Eigen::Matrix<double, N, N> project_to_psd(const Eigen::Matrix<double, N, N>& A) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> es(A);
  const auto& lambda = es.eigenvalues();
  if (lambda.minCoeff() >= 0.0) return A;
  const auto& V = es.eigenvectors();
  return V * lambda.cwiseMax(0.0).asDiagonal() * V.transpose();
}

template Eigen::Matrix<double, 9, 9> project_to_psd<9>(const Eigen::Matrix<double, 9, 9>&);

namespace {

/// Q = U ⊗ I₃, (3n)×(3n − 3): column block j of U (j = 1 … n − 1) is (1, …, 1, −j, 0, …)/√(j(j + 1))
/// with j ones, orthonormal and orthogonal to (1, …, 1).
template <int n>
Eigen::Matrix<double, 3 * n, 3 * n - 3> translation_complement() {
  Eigen::Matrix<double, 3 * n, 3 * n - 3> Q = Eigen::Matrix<double, 3 * n, 3 * n - 3>::Zero();
  for (int j = 1; j < n; ++j) {
    const double scale = 1.0 / std::sqrt(double(j * (j + 1)));
    for (int i = 0; i <= j; ++i)
      Q.template block<3, 3>(3 * i, 3 * (j - 1)) = (i < j ? scale : -j * scale) * Eigen::Matrix3d::Identity();
  }
  return Q;
}

template <int n>
void project_in_translation_complement(Eigen::Matrix<double, 12, 12>& H) {
  constexpr int d = 3 * n, r = 3 * n - 3;
  static const Eigen::Matrix<double, d, r> Q = translation_complement<n>();
  // Coefficient-based products: Eigen would send these small fixed products to its blocked GEMM.
  const Eigen::Matrix<double, d, r> HQ = H.template topLeftCorner<d, d>().lazyProduct(Q);
  const Eigen::Matrix<double, r, r> R = Q.transpose().lazyProduct(HQ);
  // The plain-loop decomposition (symmetric_eigen.hpp), unrolled for these sizes: 1.6× faster
  // than Eigen's solver on 9×9 matrices (docs/benchmarks.md, session 35).
  const SymmetricEigen<r> es = checked_symmetric_eigen<r>(R);
  const auto& lambda = es.values;
  if (lambda.minCoeff() >= 0.0) return;
  const Eigen::Matrix<double, d, r> QV = Q.lazyProduct(es.vectors);
  const Eigen::Matrix<double, r, d> LQVt = lambda.cwiseMax(0.0).asDiagonal() * QV.transpose();
  H.template topLeftCorner<d, d>() = QV.lazyProduct(LQVt);
}

}  // namespace

void project_translation_invariant_to_psd(Eigen::Matrix<double, 12, 12>& H, int active_vertices) {
  switch (active_vertices) {
    case 2: project_in_translation_complement<2>(H); break;
    case 3: project_in_translation_complement<3>(H); break;
    default: project_in_translation_complement<4>(H); break;
  }
}

}  // namespace stiffsoft::contact
