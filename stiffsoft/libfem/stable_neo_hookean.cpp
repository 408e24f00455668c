#include <stiffsoft/libfem/stable_neo_hookean.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>

#include <stiffsoft/libfem/determinant_derivatives.hpp>
#include <stiffsoft/libfem/rotation_variant_svd.hpp>

namespace stiffsoft::fem {

StableNeoHookean::StableNeoHookean(double E, double nu)
    : Material(E, nu), m_mu(lame().mu), m_lambda(lame().lambda + lame().mu), m_alpha(1 + m_mu / m_lambda) {}

double StableNeoHookean::psi(const Eigen::Matrix3d& F) const {
  // λ̂/2 (J − α)² − μ̂²/(2λ̂) expanded with α − 1 = μ̂/λ̂, so that ψ(I) is exactly 0 in floating point.
  const double Jm1 = F.determinant() - 1;
  return 0.5 * m_mu * (F.squaredNorm() - 3) - m_mu * Jm1 + 0.5 * m_lambda * Jm1 * Jm1;
}

Eigen::Matrix3d StableNeoHookean::P(const Eigen::Matrix3d& F) const {
  return m_mu * F + m_lambda * (F.determinant() - m_alpha) * cofactor(F);
}

Matrix9d StableNeoHookean::dPdF(const Eigen::Matrix3d& F) const {
  // Entry by entry, no 9×9 temporaries: λ̂ g gᵀ, then μ̂ on the diagonal, then the 36 nonzeros of
  // λ̂ (J − α) ∂²J/∂F².
  const Vector9d g = vec(cofactor(F)), lambda_g = m_lambda * g;
  Matrix9d H;
  for (int j = 0; j < 9; ++j) H.col(j) = g(j) * lambda_g;
  H.diagonal().array() += m_mu;
  add_determinant_hessian(m_lambda * (F.determinant() - m_alpha), F, H);
  return H;
}

Matrix9d StableNeoHookean::dPdF_projected(const Eigen::Matrix3d& F) const {
  // Smith, de Goes, Kim 2019 ("Analytic Eigensystems for Isotropic Distortion Energies"): with
  // F = U Σ Vᵀ, ∂P/∂F has the eigenvectors vec(U E Vᵀ) for the twist and flip of each pair of
  // axes (i, j), E = (eᵢeⱼᵀ ∓ eⱼeᵢᵀ)/√2 with eigenvalues μ̂ ± λ̂ (J − α) σ_k (k the third axis),
  // and three in the span of the scalings U eᵢeᵢᵀ Vᵀ, the eigenvectors of the 3×3 ∂²ψ/∂σ².
  // The clamped projection is ∂P/∂F less its negative modes, without a 9×9 decomposition: near
  // rest only twists can be negative (μ̂ − μ̂ σ_k there), and the scalings' block is positive
  // definite at every moderate strain.
  Matrix9d H = dPdF(F);
  const RotationVariantSvd svd = rotation_variant_svd(F);
  const Eigen::Vector3d& s = svd.sigma;
  const double c = m_lambda * (F.determinant() - m_alpha);
  // D is an expression, formed only for a negative eigenvalue.
  const auto remove = [&](double eigenvalue, const auto& D) {
    if (eigenvalue >= 0) return;
    const Vector9d d = vec(D), scaled = eigenvalue * d;
    for (int j = 0; j < 9; ++j) H.col(j) -= d(j) * scaled;  // the rank-one update, no 9×9 temporary
  };
  constexpr int pairs[3][3] = {{0, 1, 2}, {1, 2, 0}, {0, 2, 1}};
  const double r = 1 / std::sqrt(2.0);
  for (const auto& [i, j, k] : pairs) {
    const auto a = r * svd.U.col(i) * svd.V.col(j).transpose(), b = r * svd.U.col(j) * svd.V.col(i).transpose();
    remove(m_mu + c * s(k), a - b);  // twist
    remove(m_mu - c * s(k), a + b);  // flip
  }
  // ∂²ψ/∂σ² = μ̂ I + λ̂ ∇J ∇Jᵀ + λ̂ (J − α) ∇²J with J = σ₀σ₁σ₂, acting on the scalings
  // S = [vec(u₀v₀ᵀ) vec(u₁v₁ᵀ) vec(u₂v₂ᵀ)]: their block is S A Sᵀ, and S A₋ Sᵀ its negative part.
  const Eigen::Vector3d grad_J(s(1) * s(2), s(0) * s(2), s(0) * s(1));
  Eigen::Matrix3d A = m_mu * Eigen::Matrix3d::Identity() + m_lambda * grad_J * grad_J.transpose();
  for (const auto& [i, j, k] : pairs) {
    A(i, j) += c * s(k);
    A(j, i) += c * s(k);
  }
  // Positive definite (Sylvester's leading minors), as at every moderate strain: nothing to remove.
  if (A(0, 0) > 0 && A(0, 0) * A(1, 1) - A(0, 1) * A(0, 1) > 0 && A.determinant() > 0) return H;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(A);
  const Eigen::Matrix3d negative =
      es.eigenvectors() * es.eigenvalues().cwiseMin(0.0).asDiagonal() * es.eigenvectors().transpose();
  Eigen::Matrix<double, 9, 3> S;
  for (int i = 0; i < 3; ++i) S.col(i) = vec(svd.U.col(i) * svd.V.col(i).transpose());
  H.noalias() -= (S * negative).lazyProduct(S.transpose());  // coefficient-wise: 9×3 by 3×9 is too small for GEMM
  return H;
}

}  // namespace stiffsoft::fem
