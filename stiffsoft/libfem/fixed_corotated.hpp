#pragma once
/// @file Fixed corotated elasticity (Stomakhin et al. 2012, "Energetically Consistent Invertible
/// Elasticity"): ψ = μ ‖F − R‖²_F + λ/2 (J − 1)², R the polar rotation of F from the
/// rotation-variant SVD, J = det F. Defined for inverted F.

#include <stiffsoft/libfem/material.hpp>

namespace stiffsoft::fem {

/// Fixed corotated isotropic elasticity; linearises to small-strain elasticity with μ, λ.
class FixedCorotated final : public Material {
 public:
  /// E (Pa), ν in (−1, 0.5).
  FixedCorotated(double youngs_modulus, double poisson_ratio);
  /// "fixed_corotated".
  const char* name() const override { return "fixed_corotated"; }
  /// ψ = μ Σᵢ (σᵢ − 1)² + λ/2 (J − 1)² = μ ‖F − R‖² + λ/2 (J − 1)².
  double psi(const Eigen::Matrix3d& F) const override;
  /// P = 2μ (F − R) + λ (J − 1) cof F.
  Eigen::Matrix3d P(const Eigen::Matrix3d& F) const override;
  /// ∂P/∂F = 2μ (I₉ − ∂R/∂F) + λ vec(cof F) vec(cof F)ᵀ + λ (J − 1) ∂²J/∂F², with
  /// ∂R/∂F = Σ_{i<j} 2/(σᵢ + σⱼ) vec(Q_ij) vec(Q_ij)ᵀ, Q_ij = U (eᵢeⱼᵀ − eⱼeᵢᵀ) Vᵀ / √2 (the
  /// twist modes; Kim & Eberle 2020, "Dynamic Deformables"). σᵢ + σⱼ is floored at
  /// 1e-12 (σ₀ + 1): R jumps where it vanishes.
  Matrix9d dPdF(const Eigen::Matrix3d& F) const override;
};

}  // namespace stiffsoft::fem
