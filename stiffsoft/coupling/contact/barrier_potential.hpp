#pragma once
/// @file The barrier potential of one contact stencil: P(x) = m(x) · b(d²(x), d̂), with the
/// edge–edge mollifier m only on mollified EdgeEdge stencils (IPC, Li et al. 2020, eqs. 6, 13).

#include <Eigen/Core>

#include <stiffsoft/coupling/contact/barrier.hpp>
#include <stiffsoft/coupling/contact/distance_classification.hpp>
#include <stiffsoft/coupling/contact/edge_edge_mollifier.hpp>
#include <stiffsoft/coupling/contact/primitive_pair.hpp>
#include <stiffsoft/coupling/contact/psd_projection.hpp>
#include <stiffsoft/coupling/contact/squared_distance.hpp>

namespace stiffsoft::contact {

/// One contact stencil as the barrier sees it.
///
/// Mollified nearly parallel edges: IPC keeps an edge–edge candidate whose
/// ‖ea × eb‖² < ε_x as an EdgeEdge stencil with the mollifier even when its distance type is
/// degenerate (ipc-toolkit, Collisions::build). For such stencils set `segment_distance`:
/// d² is then the TRUE segment–segment squared distance, obtained by classifying the four
/// vertices on every call (classify_edge_edge) and evaluating the classified sub-pair
/// (VV / EV / EE) on the matching vertices; its gradient and Hessian are those of the
/// sub-pair scattered to the 12 coordinates (piecewise smooth, C¹ across type switches,
/// the Hessian jumps there exactly as in IPC). With `segment_distance = false` an EdgeEdge
/// stencil uses the line–line distance.
struct Stencil {
  /// primitive pair; vertices packed as documented on PrimitivePair
  PrimitivePair kind = PrimitivePair::VertexVertex;
  /// mollifier threshold ε_x, m⁴ (edge_edge_mollifier_threshold); ≤ 0: no mollifier. EdgeEdge only.
  double eps_x = 0;
  /// EdgeEdge only: use the exact segment–segment distance (classified inside) instead of the
  /// line–line distance; meant for mollified stencils whose type is not EA_EB.
  bool segment_distance = false;
};

/// Whether the stencil carries the edge–edge mollifier.
inline bool is_mollified(const Stencil& s) { return s.kind == PrimitivePair::EdgeEdge && s.eps_x > 0.0; }

/// Whether the stencil's mollifier is below 1 at x (its edges within the mollifier's angle of
/// parallel): only then do its value, gradient and Hessian carry the mollifier's terms.
bool mollifier_active(const Stencil& s, const Vector12d& x);

/// Whether d² is the classified segment–segment distance.
inline bool uses_segment_distance(const Stencil& s) {
  return s.kind == PrimitivePair::EdgeEdge && s.segment_distance;
}

/// Classification of an EdgeEdge stencil [ea0; ea1; eb0; eb1].
Classified classify_edge_edge_stencil(const Vector12d& x);

/// Squared distance d² of the stencil, m²: squared_distance(kind, x), or the classified
/// segment–segment distance when uses_segment_distance(s).
double stencil_squared_distance(const Stencil& s, const Vector12d& x);

/// ∇_x d² of the stencil, 12-vector, metres.
Vector12d stencil_squared_distance_gradient(const Stencil& s, const Vector12d& x);

/// ∇²_x d² of the stencil, 12×12, dimensionless.
Matrix12d stencil_squared_distance_hessian(const Stencil& s, const Vector12d& x);

/// Closest points of the stencil (weights over the stencil's 4 vertices, residual r, and the
/// parameters of the used pair), classified for segment-distance stencils.
ClosestPoints stencil_closest_points(const Stencil& s, const Vector12d& x);

/// Barrier potential P(x) = m(x) b(d²(x), d̂) of one stencil (m ≡ 1 unless mollified), m⁴;
/// multiply by κ for an energy. x: packed stencil, m; dhat: d̂, m.
double barrier_potential(const Stencil& s, const Vector12d& x, double dhat);

/// barrier_potential(s, x, dhat) with the stencil's d² = stencil_squared_distance(s, x) given
/// (m²), for a caller that has it already: the same value, bit for bit.
double barrier_potential(const Stencil& s, const Vector12d& x, double d2, double dhat);

/// ∇P = m b'(d²) ∇d² + b ∇m, 12-vector, m³.
Vector12d barrier_potential_gradient(const Stencil& s, const Vector12d& x, double dhat);

/// barrier_potential_gradient(s, x, dhat) with d² = stencil_squared_distance(s, x) given (m²):
/// the same gradient, bit for bit.
Vector12d barrier_potential_gradient(const Stencil& s, const Vector12d& x, double d2, double dhat);

/// ∇²P = m (b'' ∇d² ∇d²ᵀ + b' ∇²d²) + b' (∇m ∇d²ᵀ + ∇d² ∇mᵀ) + b ∇²m, 12×12, m².
/// project_psd: clamp the negative eigenvalues of the active (3·vertex_count)² block to 0
/// (unmollified stencils: by projected_barrier_hessian, in the ≤ 5-dimensional span of ∇d² and ∇²d²).
Matrix12d barrier_potential_hessian(const Stencil& s, const Vector12d& x, double dhat,
                                    bool project_psd);

/// How Newton's Hessian of a stencil's barrier is made positive semi-definite.
enum class BarrierHessian {
  /// The exact ∇²P with its negative eigenvalues clamped to 0: a (3 + M)×(3 + M)
  /// eigen-decomposition (projected_barrier_hessian.hpp), 9×9 for mollified edge pairs.
  Projected,
  /// κ B″(d) ∇d ∇dᵀ (barrier_gauss_newton_hessian): PSD by construction, no decomposition; it
  /// leaves out B′(d) ∇²d, the distance's own curvature. Mollified edge–edge stencils keep the
  /// projected Hessian. Cheaper, but it can let contacts close to nanometres: see
  /// docs/newton.md before using it.
  GaussNewton
};

/// The Gauss–Newton Hessian c(d²) ∇d² ∇d²ᵀ of a stencil that is not mollified
/// (barrier_gauss_newton_coefficient), 12×12, m²; rank one, PSD. Newton's direction changes
/// with it, not the minimiser: the energy and gradient are those of barrier_potential.
Matrix12d barrier_gauss_newton_hessian(const Stencil& s, const Vector12d& x, double dhat);

/// Newton's PSD Hessian of one stencil's barrier by `method` (stencils whose mollifier is active: Projected,
/// whose mollifier terms the Gauss–Newton form does not cover).
Matrix12d barrier_newton_hessian(const Stencil& s, const Vector12d& x, double dhat, BarrierHessian method);

}  // namespace stiffsoft::contact
