#include <stiffsoft/libabd/orthogonality_potential.hpp>

#include <Eigen/SVD>
#include <cmath>

namespace stiffsoft::abd {

namespace {
Eigen::Matrix3d gram_minus_identity(const Eigen::Matrix3d& A) {
  return A * A.transpose() - Eigen::Matrix3d::Identity();
}
/// The 9×9 A block of ∇²V⊥ with its negative eigenvalues set to zero, from its analytic
/// eigensystem (Smith, de Goes, Kim 2019): V⊥ = κν Σᵢ (σᵢ² − 1)² is isotropic in A = U Σ Vᵀ, so
/// its eigenvectors are U E Vᵀ for the scalings E = eᵢeᵢᵀ (eigenvalue 4κν (3σᵢ² − 1)), and per
/// pair of axes the symmetric E = (eᵢeⱼᵀ + eⱼeᵢᵀ)/√2 (4κν (σᵢ² + σᵢσⱼ + σⱼ² − 1)) and the
/// antisymmetric E = (eᵢeⱼᵀ − eⱼeᵢᵀ)/√2 (4κν (σᵢ² − σᵢσⱼ + σⱼ² − 1)). `scale` is 4κν. The entries
/// are over q's A part, row i of A at 3i.
Eigen::Matrix<double, 9, 9> projected_a_block(const Eigen::Matrix3d& A, double scale) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d& U = svd.matrixU();
  const Eigen::Matrix3d& V = svd.matrixV();
  const Eigen::Vector3d& s = svd.singularValues();
  Eigen::Matrix<double, 9, 9> H = Eigen::Matrix<double, 9, 9>::Zero();
  const auto add = [&](double eigenvalue, const Eigen::Matrix3d& D) {
    if (eigenvalue <= 0) return;
    // Row-major flattening of D, as q stores A.
    const Eigen::Matrix3d Dt = D.transpose();
    const Eigen::Map<const Eigen::Matrix<double, 9, 1>> d(Dt.data());
    H.noalias() += (scale * eigenvalue) * d * d.transpose();
  };
  for (int i = 0; i < 3; ++i) add(3 * s(i) * s(i) - 1, U.col(i) * V.col(i).transpose());
  const double r = 1 / std::sqrt(2.0);
  constexpr int pairs[3][2] = {{0, 1}, {1, 2}, {0, 2}};
  for (const auto& [i, j] : pairs) {
    const Eigen::Matrix3d a = r * U.col(i) * V.col(j).transpose(), b = r * U.col(j) * V.col(i).transpose();
    const double square_sum = s(i) * s(i) + s(j) * s(j) - 1;
    add(square_sum + s(i) * s(j), a + b);
    add(square_sum - s(i) * s(j), a - b);
  }
  return H;
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
  Matrix12d out = Matrix12d::Zero();
  if (project_psd) {
    out.bottomRightCorner<9, 9>() = projected_a_block(A, 4 * kappa * volume);
    return out;
  }
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
  out.bottomRightCorner<9, 9>() = H;
  return out;
}

double orthogonality_error(const Vector12d& q) {
  return gram_minus_identity(affine_matrix(q)).norm();
}

}  // namespace stiffsoft::abd
