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

/// Π₊(b'' ∇d² ∇d²ᵀ + b' ∇²d²) from the pair's distance factors, 12×12, m²; zero for
/// d ≥ d̂. db, ddb: b'(d²) and b''(d²) (barrier.hpp).
Matrix12d projected_barrier_hessian(const DistanceCurvature& k, double db, double ddb);

/// Newton's projected Hessian of an unmollified stencil's barrier, 12×12, m²: equal to
/// barrier_potential_hessian(s, x, dhat, true) to round-off, at a fraction of its cost.
/// Segment-distance stencils project their classified sub-pair's Hessian and scatter it.
Matrix12d projected_barrier_hessian(const Stencil& s, const Vector12d& x, double dhat);

}  // namespace stiffsoft::contact
