#pragma once
/// @file Stable neo-Hookean elasticity (Smith, de Goes, Kim 2018, "Stable Neo-Hookean Flesh
/// Simulation", eq. 14, without its −μ/2 log(I_C + 1) term):
/// ψ = μ̂/2 (I_C − 3) + λ̂/2 (J − α)² − μ̂²/(2λ̂), α = 1 + μ̂/λ̂, I_C = ‖F‖²_F, J = det F.
/// The constant only makes ψ(I) = 0. Defined and smooth for every F, inverted included.

#include <stiffsoft/libfem/material.hpp>

namespace stiffsoft::fem {

/// Stable neo-Hookean isotropic elasticity.
/// Linearising at F = I gives ∂P/∂F : δF = μ̂ (δF + δFᵀ) + (λ̂ − μ̂) tr(δF) I, so the
/// re-parameterisation μ̂ = μ, λ̂ = λ + μ matches small-strain elasticity with the Lamé μ, λ of
/// (E, ν) (the paper's Lamé matching applied to eq. 14; its μ̂ = 4/3 μ, λ̂ = λ + 5/6 μ hold for
/// the energy with the log term). λ̂ = E / (2(1 + ν)(1 − 2ν)) > 0 for every admissible ν.
class StableNeoHookean final : public Material {
 public:
  /// E (Pa), ν in (−1, 0.5).
  StableNeoHookean(double youngs_modulus, double poisson_ratio);
  /// "stable_neo_hookean".
  const char* name() const override { return "stable_neo_hookean"; }
  /// ψ = μ̂/2 (‖F‖² − 3) + λ̂/2 (J − α)² − μ̂²/(2λ̂) = μ̂/2 (‖F‖² − 3) − μ̂ (J − 1) + λ̂/2 (J − 1)².
  double psi(const Eigen::Matrix3d& F) const override;
  /// P = μ̂ F + λ̂ (J − α) cof F.
  Eigen::Matrix3d P(const Eigen::Matrix3d& F) const override;
  /// ∂P/∂F = μ̂ I₉ + λ̂ vec(cof F) vec(cof F)ᵀ + λ̂ (J − α) ∂²J/∂F².
  Matrix9d dPdF(const Eigen::Matrix3d& F) const override;
  /// ∂P/∂F with its negative eigenvalues set to zero, from its analytic eigensystem (Smith,
  /// de Goes, Kim 2019): six twist and flip eigenpairs in closed form and three from the 3×3
  /// ∂²ψ/∂σ² of the singular values, instead of a numerical 9×9 decomposition.
  Matrix9d dPdF_projected(const Eigen::Matrix3d& F) const override;

  /// μ̂ = μ (Pa).
  double mu_hat() const { return m_mu; }
  /// λ̂ = λ + μ (Pa).
  double lambda_hat() const { return m_lambda; }
  /// α = 1 + μ̂/λ̂, the rest volume ratio term that makes P(I) = 0.
  double alpha() const { return m_alpha; }

 private:
  double m_mu, m_lambda, m_alpha;
};

}  // namespace stiffsoft::fem
