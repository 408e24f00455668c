#pragma once
/// @file Always-on validity checks of user surfaces: closed, manifold, oriented, not self-intersecting.

#include <optional>
#include <string>

#include <stiffsoft/meshing/surface_mesh.hpp>

namespace stiffsoft {

/// Relative area below which a triangle counts as degenerate: |(b−a)×(c−a)| ≤ 1e-12 · ℓ_max²,
/// ℓ_max the longest edge (a needle or a sliver this thin has no usable normal).
inline constexpr double degenerate_area_tolerance = 1e-12;

/// The first reason `mesh` is not a closed, consistently outward-oriented 2-manifold, or nothing.
/// Checked in this order: at least one face; indices in range; no degenerate face (a repeated
/// vertex or a relative area ≤ degenerate_area_tolerance); every undirected edge has exactly two
/// faces, traversed in opposite directions (closed, edge-manifold, consistently oriented); the faces
/// around every vertex form one fan (vertex-manifold); enclosed volume > 0 (outward normals).
/// Vertices that no face uses are allowed (they do not change the surface).
/// The message names the faces, edges or vertices (0-based indices).
std::optional<std::string> closed_manifold_problem(const SurfaceMesh& mesh);

/// Throws std::runtime_error("<what>: <problem>") when closed_manifold_problem() finds one.
/// @param what the body or file the mesh comes from, for the message
void check_closed_manifold(const SurfaceMesh& mesh, const std::string& what);

/// The first pair of faces of `mesh` that intersect each other, by exact predicates
/// (CGAL Epick), or nothing. Faces are culled with CGAL::box_intersection_d on their bounding boxes.
/// Rule for neighbours: faces sharing an edge (a, b) intersect only if they are coplanar with the
/// opposite vertices on the same side of ab (a fold); faces sharing one vertex v, t1 = (v, a, b) and
/// t2 = (v, c, d), intersect if segment ab meets t2 or segment cd meets t1 (exactly when t1 ∩ t2 holds
/// a point other than v, coplanar or not); faces with no shared vertex index intersect if they
/// touch at all (so distinct vertices at the same position count). Returns the pair with the
/// smallest (face_a, face_b), face_a < face_b. Degenerate (collinear) faces are reported as
/// intersecting themselves (face_a == face_b). Indices must be in range.
std::optional<std::pair<int, int>> find_self_intersection(const SurfaceMesh& mesh);

/// Throws std::runtime_error("<what>: faces i and j intersect …") when find_self_intersection() finds a pair.
void check_not_self_intersecting(const SurfaceMesh& mesh, const std::string& what);

}  // namespace stiffsoft
