#pragma once
/// @file The constant mass matrix of an affine body, M = ∫ρ JᵀJ dV (Lan et al. 2022, eq. 3).

#include <Eigen/Core>

#include <stiffsoft/libabd/affine_body.hpp>

namespace stiffsoft::abd {

/// Mass properties of an affine body in its body frame.
struct MassProperties {
  double mass = 0;                                      ///< m = ρ ∫ dV (kg)
  Eigen::Vector3d first = Eigen::Vector3d::Zero();      ///< ρ ∫ x̄ dV (kg·m); zero when x̄ is centred at the centre of mass
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();     ///< ρ ∫ x̄ x̄ᵀ dV (kg·m²)
};

/// Mass properties from the volume moments ∫dV (m³), ∫x̄ dV (m⁴), ∫x̄x̄ᵀ dV (m⁵) and density ρ (kg/m³).
MassProperties mass_properties(double volume, const Eigen::Vector3d& first,
                               const Eigen::Matrix3d& second, double density);

/// M = ∫ρ JᵀJ dV: [[m I₃, I₃ ⊗ sᵀ], [I₃ ⊗ s, I₃ ⊗ S]] with s = ρ∫x̄, S = ρ∫x̄x̄ᵀ (12×12, SPD).
Matrix12d mass_matrix(const MassProperties& mp);

/// The body-frame inertia tensor about the frame origin, I = tr(S) I₃ − S (kg·m²).
Eigen::Matrix3d inertia_tensor(const MassProperties& mp);

}  // namespace stiffsoft::abd
