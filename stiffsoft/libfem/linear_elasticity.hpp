#pragma once
/// @file Small-strain linear elasticity: ψ = μ ε:ε + λ/2 tr(ε)², ε = sym(F) − I.
/// Not rotation invariant: use it only for small displacements (patch test, cantilever).

#include <stiffsoft/libfem/material.hpp>

namespace stiffsoft::fem {

/// Linear (small-strain) isotropic elasticity.
class LinearElasticity final : public Material {
 public:
  /// E (Pa), ν in (−1, 0.5).
  LinearElasticity(double youngs_modulus, double poisson_ratio);
  /// "linear".
  const char* name() const override { return "linear"; }
  /// ψ = μ ε:ε + λ/2 tr(ε)², ε = ½(F + Fᵀ) − I.
  double psi(const Eigen::Matrix3d& F) const override;
  /// P = 2μ ε + λ tr(ε) I.
  Eigen::Matrix3d P(const Eigen::Matrix3d& F) const override;
  /// Constant: ∂P_ij/∂F_kl = μ(δ_ik δ_jl + δ_il δ_jk) + λ δ_ij δ_kl; PSD (eigenvalues 2μ, 0 on
  /// skew F, 3λ + 2μ = 3K > 0).
  Matrix9d dPdF(const Eigen::Matrix3d& F) const override;
  /// Equal to dPdF: it is already positive semi-definite.
  Matrix9d dPdF_projected(const Eigen::Matrix3d& F) const override { return dPdF(F); }

 private:
  Matrix9d m_dPdF;
};

}  // namespace stiffsoft::fem
