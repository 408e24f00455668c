#pragma once
/// @file Projection of symmetric stencil Hessians onto the positive semi-definite cone.
/// The definitions live in psd_projection.cpp, instantiated there for N = 2, 3, 6, 9 and 12:
/// Eigen's fixed-size eigensolvers cost every file that includes this header about half a
/// minute of compile time when they are instantiated inline.

#include <Eigen/Core>

namespace stiffsoft::contact {

/// Nearest (Frobenius) positive semi-definite matrix to the symmetric N×N matrix A:
/// A = V Λ Vᵀ → V max(Λ, 0) Vᵀ (projected Newton, Teran et al. 2005; IPC §4).
/// Reads the lower triangle of A. Returns A itself, bit for bit, when it is already PSD,
/// so that projecting a PSD Hessian never perturbs it. Instantiated for N = 2, 3, 6, 9, 12.
template <int N>
Eigen::Matrix<double, N, N> project_to_psd(const Eigen::Matrix<double, N, N>& A);

/// Projects the leading (3·n)×(3·n) block of a stencil Hessian (n = active vertices, 1..4) to
/// PSD in place; the rest is zero by construction for contact stencils and stays untouched.
/// Projecting only the active block is cheaper and gives the same result as the full 12×12.
void project_leading_block_to_psd(Eigen::Matrix<double, 12, 12>& H, int active_vertices);

}  // namespace stiffsoft::contact
