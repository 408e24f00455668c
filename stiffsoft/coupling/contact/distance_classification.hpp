#pragma once
/// @file Classification of point–triangle and edge–edge candidates into the primitive pair whose
/// (line / plane) distance is the true distance (IPC, Li et al. 2020, §4.3 and Supplement), and
/// the exact point–triangle and segment–segment squared distances built on it.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <stiffsoft/coupling/contact/primitive_pair.hpp>
#include <stiffsoft/coupling/contact/squared_distance.hpp>

namespace stiffsoft::contact {

/// A candidate's distance type: the pair kind and the LOCAL indices (0..3 into the candidate's
/// four vertices: (p, t0, t1, t2) or (ea0, ea1, eb0, eb1)) that form it, in the order of the
/// kind's vertex list (VV {v0, v1}; EV {v, e0, e1}; FV {v, f0, f1, f2}; EE {ea0, ea1, eb0, eb1});
/// unused entries are −1. IPC's types map as P_T0..2 → VV, P_E0..2 → EV, P_T → FV,
/// EA?_EB? → VV, EA_EB? / EA?_EB → EV, EA_EB → EE.
struct Classified {
  /// the pair whose distance is the true distance
  PrimitivePair kind;
  /// local vertex indices of that pair, −1 where unused
  std::array<int, 4> local;
};

/// Packs the classified sub-pair's vertices of a candidate stencil into a stencil of its own.
inline Vector12d gather_classified(const Classified& c, const Vector12d& x) {
  Vector12d y = Vector12d::Zero();
  for (int i = 0; i < vertex_count(c.kind); ++i) y.segment<3>(3 * i) = x.segment<3>(3 * c.local[i]);
  return y;
}

/// Adds a sub-pair gradient back into the candidate's 12 coordinates.
inline Vector12d scatter_classified(const Classified& c, const Vector12d& g_sub) {
  Vector12d g = Vector12d::Zero();
  for (int i = 0; i < vertex_count(c.kind); ++i) g.segment<3>(3 * c.local[i]) += g_sub.segment<3>(3 * i);
  return g;
}

/// Adds a sub-pair Hessian back into the candidate's 12×12 coordinates.
inline Matrix12d scatter_classified(const Classified& c, const Matrix12d& H_sub) {
  Matrix12d H = Matrix12d::Zero();
  const int n = vertex_count(c.kind);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      H.block<3, 3>(3 * c.local[i], 3 * c.local[j]) += H_sub.block<3, 3>(3 * i, 3 * j);
  return H;
}

namespace detail {

/// Keeps the smallest candidate distance and its classification.
struct BestCandidate {
  double d2 = std::numeric_limits<double>::infinity();
  Classified type{PrimitivePair::VertexVertex, {-1, -1, -1, -1}};
  void offer(double candidate_d2, PrimitivePair kind, std::array<int, 4> local) {
    if (candidate_d2 < d2) {
      d2 = candidate_d2;
      type = {kind, local};
    }
  }
};

/// Offers the point–segment candidates of point `v` and edge (e0, e1): EV when the
/// projection falls strictly inside the edge, otherwise nothing (the endpoints are offered
/// as VV candidates by the callers).
inline void offer_point_edge(BestCandidate& best, const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                             const Eigen::Vector3d& e1, std::array<int, 4> local) {
  const Eigen::Vector3d e = e1 - e0;
  const double ee = e.squaredNorm();
  if (!(ee > 0.0)) return;
  const double t = (p - e0).dot(e) / ee;
  if (t > 0.0 && t < 1.0) best.offer((p - e0 - t * e).squaredNorm(), PrimitivePair::EdgeVertex, local);
}

}  // namespace detail

/// Distance type of point p against triangle (t0, t1, t2); local indices p = 0, t_i = 1 + i.
/// FV when p projects strictly inside the triangle (barycentrics > 0), else the nearest of the
/// edges (EV, projection strictly inside the edge) and vertices (VV). A degenerate
/// (zero-area) triangle is treated as its three edges.
inline Classified classify_point_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                          const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) {
  const Eigen::Vector3d a = t1 - t0, b = t2 - t0, w = p - t0;
  const double aa = a.squaredNorm(), ab = a.dot(b), bb = b.squaredNorm();
  const double det = aa * bb - ab * ab;
  // Same conditioning rule as the Gram inverse in squared_distance.hpp: a sliver this thin
  // is handled through its edges, which give the same distance to working precision.
  if (det > 1e-14 * aa * bb) {
    const double wa = w.dot(a), wb = w.dot(b);
    const double beta1 = (bb * wa - ab * wb) / det, beta2 = (aa * wb - ab * wa) / det;
    if (beta1 > 0.0 && beta2 > 0.0 && beta1 + beta2 < 1.0)
      return {PrimitivePair::FaceVertex, {0, 1, 2, 3}};
  }
  detail::BestCandidate best;
  best.offer((p - t0).squaredNorm(), PrimitivePair::VertexVertex, {0, 1, -1, -1});
  best.offer((p - t1).squaredNorm(), PrimitivePair::VertexVertex, {0, 2, -1, -1});
  best.offer((p - t2).squaredNorm(), PrimitivePair::VertexVertex, {0, 3, -1, -1});
  detail::offer_point_edge(best, p, t0, t1, {0, 1, 2, -1});
  detail::offer_point_edge(best, p, t1, t2, {0, 2, 3, -1});
  detail::offer_point_edge(best, p, t2, t0, {0, 3, 1, -1});
  return best.type;
}

/// Distance type of segments (ea0, ea1) and (eb0, eb1); local indices 0, 1, 2, 3.
/// EE when the closest points of the two lines are strictly inside both segments (and the
/// lines are not parallel to working precision, sin²θ > 1e-14), else the nearest of the
/// endpoint-against-segment (EV) and endpoint-against-endpoint (VV) candidates.
inline Classified classify_edge_edge(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                     const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1) {
  const Eigen::Vector3d a = ea1 - ea0, b = eb1 - eb0, w = ea0 - eb0;
  const double aa = a.squaredNorm(), ab = a.dot(b), bb = b.squaredNorm();
  const double det = aa * bb - ab * ab;  // ‖a × b‖²
  if (det > 1e-14 * aa * bb) {
    const double wa = w.dot(a), wb = w.dot(b);
    // Normal equations of min ‖w + s a − t b‖²: [aa −ab; −ab bb] (s, t) = (−wa, wb).
    const double s = (ab * wb - bb * wa) / det, t = (aa * wb - ab * wa) / det;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) return {PrimitivePair::EdgeEdge, {0, 1, 2, 3}};
  }
  detail::BestCandidate best;
  best.offer((ea0 - eb0).squaredNorm(), PrimitivePair::VertexVertex, {0, 2, -1, -1});
  best.offer((ea0 - eb1).squaredNorm(), PrimitivePair::VertexVertex, {0, 3, -1, -1});
  best.offer((ea1 - eb0).squaredNorm(), PrimitivePair::VertexVertex, {1, 2, -1, -1});
  best.offer((ea1 - eb1).squaredNorm(), PrimitivePair::VertexVertex, {1, 3, -1, -1});
  detail::offer_point_edge(best, ea0, eb0, eb1, {0, 2, 3, -1});
  detail::offer_point_edge(best, ea1, eb0, eb1, {1, 2, 3, -1});
  detail::offer_point_edge(best, eb0, ea0, ea1, {2, 0, 1, -1});
  detail::offer_point_edge(best, eb1, ea0, ea1, {3, 0, 1, -1});
  return best.type;
}

/// Squared distance from the segment (q0, q1) to the line through p with unit direction u, m².
inline double segment_line_squared_distance(const Eigen::Vector3d& q0, const Eigen::Vector3d& q1,
                                            const Eigen::Vector3d& p, const Eigen::Vector3d& u) {
  const Eigen::Vector3d w0 = q0 - p, w1 = q1 - p;
  const Eigen::Vector3d r0 = w0 - w0.dot(u) * u, dr = (w1 - w1.dot(u) * u) - r0;  // across the line
  const double dd = dr.squaredNorm();
  const double t = dd > 0 ? std::clamp(-r0.dot(dr) / dd, 0.0, 1.0) : 0.0;
  return (r0 + t * dr).squaredNorm();
}

/// A lower bound of the squared distance between the segments (ea0, ea1) and (eb0, eb1), m²:
/// the larger of each segment's squared distance to the other's line (0 for a zero-length
/// segment's line). About a third of classify_edge_edge's work; a pair it puts beyond d̂ is
/// no contact.
inline double segment_segment_squared_distance_lower_bound(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                                           const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1) {
  const Eigen::Vector3d a = ea1 - ea0, b = eb1 - eb0;
  const double aa = a.squaredNorm(), bb = b.squaredNorm();
  double bound = 0;
  if (aa > 0) bound = segment_line_squared_distance(eb0, eb1, ea0, a / std::sqrt(aa));
  if (bb > 0) bound = std::max(bound, segment_line_squared_distance(ea0, ea1, eb0, b / std::sqrt(bb)));
  return bound;
}

/// Squared distance from p to the plane through o spanned by a and b, m²; 0 when a and b are
/// within about 1e-4 rad of parallel (or one is zero), where the computed normal a × b could
/// tilt enough to overstate it. The shared core of the two plane bounds below.
inline double plane_squared_distance_bound(const Eigen::Vector3d& p, const Eigen::Vector3d& o, const Eigen::Vector3d& a,
                                           const Eigen::Vector3d& b) {
  const Eigen::Vector3d n = a.cross(b);
  const double nn = n.squaredNorm();
  if (!(nn > 1e-8 * a.squaredNorm() * b.squaredNorm())) return 0;
  const double h = n.dot(p - o);
  return h * h / nn;
}

/// A lower bound of the squared distance between the segments (ea0, ea1) and (eb0, eb1), m²:
/// the squared distance between their lines (eb0's distance to the plane through ea0 spanned
/// by both directions); 0 for edges within about 1e-4 rad of parallel. A dozen products and
/// no square root: the first test for the edge pairs of a pile, most of which it puts beyond
/// d̂ (87 % of full's candidates).
inline double line_line_squared_distance_lower_bound(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                                     const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1) {
  return plane_squared_distance_bound(eb0, ea0, ea1 - ea0, eb1 - eb0);
}

/// A lower bound on the squared distance from p to the triangle (t0, t1, t2), m²: its squared
/// distance to the triangle's plane; 0 for a triangle with an angle below about 1e-4 rad. A
/// few products against classify_point_triangle's work; a pair it puts beyond d̂ is no contact.
inline double point_triangle_squared_distance_lower_bound(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                                          const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) {
  return plane_squared_distance_bound(p, t0, t1 - t0, t2 - t0);
}

/// Exact squared distance between point p and the closed triangle (t0, t1, t2), m², any
/// configuration (degenerate triangles included).
inline double point_triangle_squared_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                              const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) {
  const Classified c = classify_point_triangle(p, t0, t1, t2);
  return squared_distance(c.kind, gather_classified(c, pack_stencil(p, t0, t1, t2)));
}

/// Exact squared distance between the closed segments (ea0, ea1) and (eb0, eb1), m², any
/// configuration (parallel and zero-length segments included).
inline double segment_segment_squared_distance(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                               const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1) {
  const Classified c = classify_edge_edge(ea0, ea1, eb0, eb1);
  return squared_distance(c.kind, gather_classified(c, pack_stencil(ea0, ea1, eb0, eb1)));
}

}  // namespace stiffsoft::contact
