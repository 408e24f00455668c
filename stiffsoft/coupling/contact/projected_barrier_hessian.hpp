#pragma once
/// @file Newton's PSD Hessian of one unmollified barrier stencil, projected in the ≤ 5
/// dimensions where it lives instead of the 9 of its vertices' relative motion.
///
/// With b = b(d²) and DistanceCurvature's factors, the exact Hessian is
///   ∇²b = b'' ∇d² ∇d²ᵀ + b' ∇²d² = C (4 b'' r rᵀ + 2 b' I₃) Cᵀ − 2 b' B P Bᵀ,   C = c ⊗ I₃.
/// Its columns lie in span{ĉ ⊗ e_j} ⊕ span{q_l ⊗ r̂}, with ĉ = c/‖c‖, r̂ = r/‖r‖ and q_l
/// orthonormal over the D_k less their parts along c: B_k = D_k ⊗ r + c ⊗ E_k has the
/// coordinates ((cᵀD_k) r + ‖c‖² E_k)/‖c‖ on the first three and ‖r‖ (q_l · D_k) on the others
/// (q_l ⊥ c). Clamping the negative eigenvalues of this (3 + M)×(3 + M) matrix S gives the
/// same matrix as clamping those of the whole 12×12 one (it is zero outside the span), to
/// round-off: a 5×5 eigen-decomposition per face–vertex or edge–edge contact instead of 9×9.

#include <stiffsoft/coupling/contact/barrier_potential.hpp>

namespace stiffsoft::contact {

/// A PSD Hessian by its positive eigenpairs: H = Σ_{m < rank} λ_m g_m g_mᵀ, g_mᵀ the rows of G.
struct LowRankHessian {
  int rank = 0;                    ///< how many terms (≤ 5)
  Eigen::Matrix<double, 5, 12> G;  ///< g_mᵀ (first `rank` rows used)
  Eigen::Matrix<double, 5, 1> lambda;  ///< λ_m > 0 (first `rank` used)
  /// Σ λ_m g_m g_mᵀ as a 12×12 matrix.
  Matrix12d formed() const;
};

/// Π₊(b'' ∇d² ∇d²ᵀ + b' ∇²d²) from the pair's distance factors, by its positive eigenpairs;
/// rank 0 for d ≥ d̂. db, ddb: b'(d²) and b''(d²) (barrier.hpp).
LowRankHessian projected_barrier_factors(const DistanceCurvature& k, double db, double ddb);

/// projected_barrier_factors(k, db, ddb).formed(), 12×12, m².
Matrix12d projected_barrier_hessian(const DistanceCurvature& k, double db, double ddb);

/// The eigenpairs of projected_barrier_hessian(s, x, dhat) for an unmollified stencil.
LowRankHessian projected_barrier_factors(const Stencil& s, const Vector12d& x, double dhat);

/// Newton's projected Hessian of an unmollified stencil's barrier, 12×12, m²: equal to
/// barrier_potential_hessian(s, x, dhat, true) to round-off, at a fraction of its cost.
/// Segment-distance stencils project their classified sub-pair's Hessian and scatter it.
Matrix12d projected_barrier_hessian(const Stencil& s, const Vector12d& x, double dhat);

}  // namespace stiffsoft::contact
