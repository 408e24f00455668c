#pragma once
/// @file The rotation-variant SVD F = U Σ Vᵀ with U, V proper rotations (Irving et al. 2004),
/// the form every corotational model needs so that it stays defined for inverted F.

#include <Eigen/Core>

namespace stiffsoft::fem {

/// F = U diag(σ) Vᵀ with det U = det V = +1. σ₀ ≥ σ₁ ≥ |σ₂|; σ₂ < 0 exactly when det F < 0.
struct RotationVariantSvd {
  Eigen::Matrix3d U;      ///< left rotation
  Eigen::Vector3d sigma;  ///< signed singular values, sorted by magnitude
  Eigen::Matrix3d V;      ///< right rotation
};

/// The rotation-variant SVD of F: the ordinary SVD with a reflection in U or V moved into σ₂.
RotationVariantSvd rotation_variant_svd(const Eigen::Matrix3d& F);

}  // namespace stiffsoft::fem
