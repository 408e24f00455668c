#pragma once
/// @file Broad phase: body pairs first (the seed's i-AABB culling: boxes of the transformed
/// bodies), then primitive pairs inside each overlapping body pair by sort-and-sweep, and those
/// of a soft body against itself through a uniform grid over the body.

#include <Eigen/Core>
#include <array>
#include <vector>

#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// Primitive pairs whose boxes overlap: between two different bodies, at least one of which
/// carries DOFs, or inside one soft body (self-contact) when they share no vertex.
struct Candidates {
  std::vector<std::array<int, 2>> vertex_face;  ///< (vertex, face)
  std::vector<std::array<int, 2>> edge_edge;    ///< (edge, edge), first < second
  /// Appends the pairs of `more` after this one's.
  void append(const Candidates& more) {
    vertex_face.insert(vertex_face.end(), more.vertex_face.begin(), more.vertex_face.end());
    edge_edge.insert(edge_edge.end(), more.edge_edge.begin(), more.edge_edge.end());
  }
};

/// Candidates for the motion of every surface vertex on the segment x0 → x1 (|V|×3 each, m):
/// a vertex's box spans both ends, grown by `inflation` (m) on every side. For proximity
/// (x1 = x0) an inflation of d̂/2 finds every pair closer than d̂. The pairs come body pair by
/// body pair, in an order fixed by the model and the boxes, not by the thread schedule.
Candidates broad_phase(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                       double inflation);

}  // namespace stiffsoft
