#include <stiffsoft/libfem/stable_neo_hookean.hpp>

#include <Eigen/LU>

#include <stiffsoft/libfem/determinant_derivatives.hpp>

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
  const Vector9d g = vec(cofactor(F));
  return m_mu * Matrix9d::Identity() + m_lambda * g * g.transpose() +
         m_lambda * (F.determinant() - m_alpha) * determinant_hessian(F);
}

}  // namespace stiffsoft::fem
