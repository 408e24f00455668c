#include <stiffsoft/coupling/contact/symmetric_eigen.hpp>

#include <Eigen/Eigenvalues>

namespace stiffsoft::contact {

template <int N>
SymmetricEigen<N> checked_symmetric_eigen(const Eigen::Matrix<double, N, N>& A) {
  SymmetricEigen<N> es = symmetric_eigen<N>(A);
  if (es.converged) return es;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eigen(A);
  es.values = eigen.eigenvalues();
  es.vectors = eigen.eigenvectors();
  es.converged = true;
  return es;
}

template SymmetricEigen<3> checked_symmetric_eigen<3>(const Eigen::Matrix3d&);
template SymmetricEigen<4> checked_symmetric_eigen<4>(const Eigen::Matrix4d&);
template SymmetricEigen<5> checked_symmetric_eigen<5>(const Eigen::Matrix<double, 5, 5>&);
template SymmetricEigen<6> checked_symmetric_eigen<6>(const Eigen::Matrix<double, 6, 6>&);
template SymmetricEigen<9> checked_symmetric_eigen<9>(const Eigen::Matrix<double, 9, 9>&);

}  // namespace stiffsoft::contact
