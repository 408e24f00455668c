#pragma once
/// @file Exact intersection and containment tests between closed surfaces (the "no body overlaps
/// another" check of `stiffsoft check` and of the first step).

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <stiffsoft/meshing/surface_mesh.hpp>

namespace stiffsoft {

/// A pair of triangles of two different surfaces that intersect (exact predicates).
struct TriangleIntersection {
  /// index of the first surface in the list, < surface_b
  int surface_a;
  /// face of surface_a
  int face_a;
  /// index of the second surface in the list
  int surface_b;
  /// face of surface_b
  int face_b;
};

/// The first intersecting pair of triangles between two DIFFERENT surfaces of the list (positions in
/// world coordinates), or nothing. Culls by surface bounding boxes first (only triangles whose box
/// meets another surface's box take part), then triangle boxes (CGAL::box_intersection_d), then
/// CGAL::do_intersect(Triangle_3, Triangle_3) with exact predicates (Epick). Touching counts as
/// intersecting. "First" is the smallest (surface_a, surface_b, face_a, face_b), so the answer does
/// not depend on the order the culling visits pairs. Faces must not be degenerate.
std::optional<TriangleIntersection> find_intersection(const std::vector<SurfaceMesh>& surfaces);

/// One surface lying inside another closed surface without their triangles meeting.
struct SurfaceContainment {
  /// the surface inside
  int inner;
  /// a vertex of `inner` strictly inside `outer`
  int vertex;
  /// the closed surface that contains it
  int outer;
};

/// The first surface found (smallest inner, then outer) with a connected component strictly inside
/// another surface, or nothing. Tests one vertex per connected component of `inner` whose bounding
/// box lies in the box of `outer`, with CGAL::Side_of_triangle_mesh (exact predicates, ray parity
/// with degenerate rays re-shot). `outer` must be closed (check_closed_manifold). Only meaningful
/// when find_intersection() found nothing: a component that crosses `outer` has vertices on both sides.
std::optional<SurfaceContainment> find_containment(const std::vector<SurfaceMesh>& surfaces);

/// Two surfaces overlap: their triangles intersect, or one lies inside the other.
using SurfaceOverlap = std::variant<TriangleIntersection, SurfaceContainment>;

/// find_intersection(), then, when that finds nothing, find_containment(): the initial "no two bodies
/// overlap" check. Frames written by a running simulation need only find_intersection() (a body
/// cannot jump inside another without crossing its surface).
std::optional<SurfaceOverlap> find_overlap(const std::vector<SurfaceMesh>& surfaces);

/// A one-line message for an overlap, naming the surfaces by `names` (same order as the surface
/// list; indices are used where names is shorter) and the faces or vertex.
std::string describe(const SurfaceOverlap& overlap, const std::vector<std::string>& names = {});

}  // namespace stiffsoft
