#include <stiffsoft/libabd/orthogonality_potential.hpp>

#include <Eigen/Eigenvalues>

namespace stiffsoft::abd {

namespace {
Eigen::Matrix3d gram_minus_identity(const Eigen::Matrix3d& A) {
  return A * A.transpose() - Eigen::Matrix3d::Identity();
}
}  // namespace

double orthogonality_potential(const Vector12d& q, double kappa, double volume) {
  return kappa * volume * gram_minus_identity(affine_matrix(q)).squaredNorm();
}

Vector12d orthogonality_potential_gradient(const Vector12d& q, double kappa, double volume) {
  const Eigen::Matrix3d A = affine_matrix(q);
  const Eigen::Matrix3d G = gram_minus_identity(A);
  // Row i of G A is Σⱼ Gᵢⱼ aⱼᵀ.
  const Eigen::Matrix3d GA = 4 * kappa * volume * G * A;
  Vector12d g = Vector12d::Zero();
  for (int i = 0; i < 3; ++i) g.segment<3>(3 + 3 * i) = GA.row(i).transpose();
  return g;
}

Matrix12d orthogonality_potential_hessian(const Vector12d& q, double kappa, double volume,
                                          bool project_psd) {
  const Eigen::Matrix3d A = affine_matrix(q);
  const Eigen::Matrix3d G = gram_minus_identity(A);
  const Eigen::Matrix3d sum_aa = A.transpose() * A;  // Σⱼ aⱼ aⱼᵀ
  Eigen::Matrix<double, 9, 9> H;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      Eigen::Matrix3d block = A.row(k).transpose() * A.row(i) + G(i, k) * Eigen::Matrix3d::Identity();
      if (i == k) block += sum_aa;
      H.block<3, 3>(3 * i, 3 * k) = block;
    }
  H *= 4 * kappa * volume;
  if (project_psd) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> es(H);
    const Eigen::Matrix<double, 9, 1> lambda = es.eigenvalues().cwiseMax(0.0);
    H = es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
  }
  Matrix12d out = Matrix12d::Zero();
  out.bottomRightCorner<9, 9>() = H;
  return out;
}

double orthogonality_error(const Vector12d& q) {
  return gram_minus_identity(affine_matrix(q)).norm();
}

}  // namespace stiffsoft::abd
