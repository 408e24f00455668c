#pragma once
/// @file The linear (4-node, constant-strain) tetrahedron: F = D_s D_m⁻¹, element energy
/// V ψ(F), its 12-gradient and 12×12 Hessian. DOFs are node-major: x = (x₀, x₁, x₂, x₃) ∈ ℝ¹².

#include <Eigen/Core>

#include <stiffsoft/libfem/material.hpp>
#include <stiffsoft/libfem/types.hpp>

namespace stiffsoft::fem {

/// Rest-state data of one linear tetrahedron.
struct TetElement {
  Eigen::Matrix3d D_m_inv = Eigen::Matrix3d::Identity();  ///< D_m⁻¹, D_m = [X₁−X₀, X₂−X₀, X₃−X₀] (1/m)
  double volume = 0;                                      ///< rest volume V = |det D_m| / 6 (m³)
};

/// Rest data from the rest positions X (node-major, m). `index` only names the element in errors.
/// Throws std::invalid_argument when the tet is degenerate: V ≤ 1e-12 ℓ³, ℓ its longest edge.
TetElement make_tet_element(const Vector12d& X, int index);

/// D_s = [x₁−x₀, x₂−x₀, x₃−x₀] (m).
Eigen::Matrix3d deformed_shape_matrix(const Vector12d& x);

/// F = D_s D_m⁻¹ (dimensionless).
Eigen::Matrix3d deformation_gradient(const TetElement& element, const Vector12d& x);

/// ∂vec(F)/∂x, 9×12, constant per element (1/m): ∂F_ij/∂x_{a,i} = (D_m⁻¹)_{a−1,j} for a = 1..3,
/// and −Σ_k (D_m⁻¹)_{kj} for a = 0.
Matrix9x12d deformation_gradient_jacobian(const TetElement& element);

/// Element energy V ψ(F) (J).
double tet_energy(const TetElement& element, const Material& material, const Vector12d& x);

/// ∂(V ψ)/∂x = V (∂F/∂x)ᵀ vec(P) (N).
Vector12d tet_gradient(const TetElement& element, const Material& material, const Vector12d& x);

/// ∂²(V ψ)/∂x² = V (∂F/∂x)ᵀ (∂P/∂F) (∂F/∂x) (N/m). With `project_psd`, ∂P/∂F is projected to PSD
/// first, which makes the 12×12 PSD too (a congruence).
Matrix12d tet_hessian(const TetElement& element, const Material& material, const Vector12d& x,
                      bool project_psd);

/// w ∂²(V ψ)/∂x² into H, formed in place: the element Hessian weighted as in an incremental
/// potential (w = β h²) without a 12×12 copy or a scaling pass. w = 1 gives tet_hessian's
/// value bit for bit.
void tet_hessian(const TetElement& element, const Material& material, const Vector12d& x, bool project_psd,
                 double weight, Matrix12d& H);

}  // namespace stiffsoft::fem
