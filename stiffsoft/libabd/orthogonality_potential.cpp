#include <stiffsoft/libabd/orthogonality_potential.hpp>

#include <cmath>

#include <stiffsoft/libfem/rotation_variant_svd.hpp>

namespace stiffsoft::abd {

namespace {
Eigen::Matrix3d gram_minus_identity(const Eigen::Matrix3d& A) {
  return A * A.transpose() - Eigen::Matrix3d::Identity();
}
/// The 9×9 A block of ∇²V⊥ / (4κν), exact, with the entries over q's A part (row i of A at 3i):
/// block (i, k) = δᵢₖ Σⱼ aⱼaⱼᵀ + a_k aᵢᵀ + Gᵢₖ I₃.
Eigen::Matrix<double, 9, 9> exact_a_block(const Eigen::Matrix3d& A) {
  const Eigen::Matrix3d G = gram_minus_identity(A);
  const Eigen::Matrix3d sum_aa = A.transpose() * A;  // Σⱼ aⱼ aⱼᵀ
  Eigen::Matrix<double, 9, 9> H;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      Eigen::Matrix3d block = A.row(k).transpose() * A.row(i) + G(i, k) * Eigen::Matrix3d::Identity();
      if (i == k) block += sum_aa;
      H.block<3, 3>(3 * i, 3 * k) = block;
    }
  return H;
}

/// exact_a_block(A) with its negative eigenvalues set to zero, from its analytic eigensystem
/// (Smith, de Goes, Kim 2019): V⊥ = κν Σᵢ (σᵢ² − 1)² is isotropic in A = U Σ Vᵀ, so its
/// eigenvectors are U E Vᵀ for the scalings E = eᵢeᵢᵀ (eigenvalue 3σᵢ² − 1), and per pair of
/// axes the symmetric E = (eᵢeⱼᵀ + eⱼeᵢᵀ)/√2 (σᵢ² + σᵢσⱼ + σⱼ² − 1) and the antisymmetric
/// E = (eᵢeⱼᵀ − eⱼeᵢᵀ)/√2 (σᵢ² − σᵢσⱼ + σⱼ² − 1). Only the negative ones are formed and taken
/// out of the exact block: near a rotation they are at most the three antisymmetric ones.
Eigen::Matrix<double, 9, 9> projected_a_block(const Eigen::Matrix3d& A) {
  Eigen::Matrix<double, 9, 9> H = exact_a_block(A);
  // Any A = U Σ Vᵀ with U, V orthogonal and Σ diagonal will do, signed σ included: the one-sided
  // Jacobi SVD of the elements (430 ns against Eigen's JacobiSVD 830 ns near rotations).
  const fem::RotationVariantSvd svd = fem::rotation_variant_svd(A);
  const Eigen::Matrix3d& U = svd.U;
  const Eigen::Matrix3d& V = svd.V;
  const Eigen::Vector3d& s = svd.sigma;
  // D is an expression, formed only for a negative eigenvalue.
  const auto remove = [&](double eigenvalue, const auto& D) {
    if (eigenvalue >= 0) return;
    // Row-major flattening of D, as q stores A.
    const Eigen::Matrix3d Dt = D.transpose();
    const Eigen::Map<const Eigen::Matrix<double, 9, 1>> d(Dt.data());
    H.noalias() -= eigenvalue * d * d.transpose();
  };
  for (int i = 0; i < 3; ++i) remove(3 * s(i) * s(i) - 1, U.col(i) * V.col(i).transpose());
  const double r = 1 / std::sqrt(2.0);
  constexpr int pairs[3][2] = {{0, 1}, {1, 2}, {0, 2}};
  for (const auto& [i, j] : pairs) {
    const double square_sum = s(i) * s(i) + s(j) * s(j) - 1;
    const auto a = r * U.col(i) * V.col(j).transpose(), b = r * U.col(j) * V.col(i).transpose();
    remove(square_sum + s(i) * s(j), a + b);
    remove(square_sum - s(i) * s(j), a - b);
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
  out.bottomRightCorner<9, 9>() = 4 * kappa * volume * (project_psd ? projected_a_block(A) : exact_a_block(A));
  return out;
}

double orthogonality_error(const Vector12d& q) {
  return gram_minus_identity(affine_matrix(q)).norm();
}

}  // namespace stiffsoft::abd
