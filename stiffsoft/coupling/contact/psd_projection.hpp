#pragma once
/// @file Projection of symmetric stencil Hessians onto the positive semi-definite cone.
/// The definitions live in psd_projection.cpp, instantiated there for N = 9:
/// Eigen's fixed-size eigensolvers cost every file that includes this header about half a
/// minute of compile time when they are instantiated inline.

#include <Eigen/Core>

namespace stiffsoft::contact {

/// Nearest (Frobenius) positive semi-definite matrix to the symmetric N×N matrix A:
/// A = V Λ Vᵀ → V max(Λ, 0) Vᵀ (projected Newton, Teran et al. 2005; IPC §4).
/// Reads the lower triangle of A. Returns A itself, bit for bit, when it is already PSD,
/// so that projecting a PSD Hessian never perturbs it. Instantiated for N = 9 (the tests'
/// reference for the 9×9 case); mollified barrier stencils use
/// project_translation_invariant_to_psd, the others projected_barrier_hessian, and friction's
/// 2×2 core is projected in closed form (friction_hessian_factors).
template <int N>
Eigen::Matrix<double, N, N> project_to_psd(const Eigen::Matrix<double, N, N>& A);

/// Projects the Hessian of a translation-invariant stencil energy (the barrier: distances and
/// the mollifier only depend on differences of positions) to PSD in place. Only the leading
/// (3·n)×(3·n) block (n = active vertices, 2..4) is non-zero and it annihilates the common
/// translations of those vertices, so it is projected in their orthogonal complement,
/// H = Q R Qᵀ with Q = U ⊗ I₃ and U's n − 1 orthonormal (Helmert) columns orthogonal to
/// (1, …, 1): R is (3n − 3)×(3n − 3), a 9×9 eigen-decomposition instead of a 12×12 one for
/// face–vertex and edge–edge stencils, with the same result as projecting the whole matrix.
/// Leaves H untouched, bit for bit, when R is already PSD.
void project_translation_invariant_to_psd(Eigen::Matrix<double, 12, 12>& H, int active_vertices);

}  // namespace stiffsoft::contact
