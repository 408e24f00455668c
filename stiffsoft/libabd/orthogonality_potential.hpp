#pragma once
/// @file The orthogonality potential that makes an affine body rigid (Lan et al. 2022, eq. 6):
/// V⊥(q) = κ ν ‖A Aᵀ − I₃‖²_F = κ ν (Σᵢ (aᵢ·aᵢ − 1)² + Σ_{i≠j} (aᵢ·aⱼ)²).
/// It depends on A only: the p entries of the gradient and Hessian are zero.

#include <stiffsoft/libabd/affine_body.hpp>

namespace stiffsoft::abd {

/// V⊥ for stiffness κ (Pa) and volume ν (m³); joules.
double orthogonality_potential(const Vector12d& q, double kappa, double volume);

/// ∂V⊥/∂aᵢ = 4κν Σⱼ Gᵢⱼ aⱼ with G = AAᵀ − I₃.
Vector12d orthogonality_potential_gradient(const Vector12d& q, double kappa, double volume);

/// ∂²V⊥/∂aᵢ∂a_k = 4κν (δᵢₖ Σⱼ aⱼaⱼᵀ + a_k aᵢᵀ + Gᵢₖ I₃); projected to PSD (negative eigenvalues of
/// the 9×9 A block set to zero) when `project_psd`, from the analytic eigensystem of the
/// isotropic V⊥ = κν Σᵢ (σᵢ² − 1)² in the singular values of A (Smith et al. 2019).
Matrix12d orthogonality_potential_hessian(const Vector12d& q, double kappa, double volume,
                                          bool project_psd);

/// ‖A Aᵀ − I₃‖_F: how far A is from a rotation (the rigidity error).
double orthogonality_error(const Vector12d& q);

}  // namespace stiffsoft::abd
