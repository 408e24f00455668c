#pragma once
/// @file Derivatives of J = det F, shared by the volume terms of the nonlinear materials.

#include <Eigen/Core>

#include <stiffsoft/libfem/types.hpp>

namespace stiffsoft::fem {

/// ∂J/∂F = cof F = J F⁻ᵀ, defined for every F (singular included):
/// columns f₁ × f₂, f₂ × f₀, f₀ × f₁ where f_i are the columns of F.
Eigen::Matrix3d cofactor(const Eigen::Matrix3d& F);

/// ∂²J/∂F² = ∂vec(cof F)/∂vec(F), 9×9, linear in F (the "cross-product" matrix of Smith et al.
/// 2019, "Analytic Eigensystems for Isotropic Distortion Energies"):
/// \f[ H_J = \begin{pmatrix} 0 & -[f_2]_\times & [f_1]_\times \\ [f_2]_\times & 0 & -[f_0]_\times
///   \\ -[f_1]_\times & [f_0]_\times & 0 \end{pmatrix} \f]
Matrix9d determinant_hessian(const Eigen::Matrix3d& F);

/// H += s ∂²J/∂F², touching only its 36 nonzeros (six cross-product blocks): what a material's
/// ∂P/∂F adds without forming the 9×9 (each entry gets the same rounding as H + s · H_J).
void add_determinant_hessian(double s, const Eigen::Matrix3d& F, Matrix9d& H);

}  // namespace stiffsoft::fem
