// The only translation unit of the meshing library that includes CGAL (compile time): exact
// triangle–triangle tests, box culling and point-in-surface queries.
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <map>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <stiffsoft/meshing/intersection.hpp>
#include <stiffsoft/meshing/mesh_checks.hpp>

namespace stiffsoft {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Segment = K::Segment_3;
using Triangle = K::Triangle_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

Point point(const SurfaceMesh& m, int v) { return Point(m.V(v, 0), m.V(v, 1), m.V(v, 2)); }

Triangle triangle(const SurfaceMesh& m, int f) {
  return Triangle(point(m, m.F(f, 0)), point(m, m.F(f, 1)), point(m, m.F(f, 2)));
}

CGAL::Bbox_3 face_box(const SurfaceMesh& m, int f) {
  return point(m, m.F(f, 0)).bbox() + point(m, m.F(f, 1)).bbox() + point(m, m.F(f, 2)).bbox();
}

CGAL::Bbox_3 surface_box(const SurfaceMesh& m) {
  CGAL::Bbox_3 box;  // empty: +inf minima, -inf maxima
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) box += face_box(m, static_cast<int>(f));
  return box;
}

bool contains(const CGAL::Bbox_3& outer, const CGAL::Bbox_3& inner) {
  for (int d = 0; d < 3; ++d)
    if (inner.min(d) < outer.min(d) || inner.max(d) > outer.max(d)) return false;
  return true;
}

// Faces f and g of the same mesh (f != g) intersect beyond what they share; see find_self_intersection().
bool faces_intersect(const SurfaceMesh& m, int f, int g) {
  int shared_f[3], shared_g[3], n_shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (m.F(f, i) == m.F(g, j)) {
        shared_f[n_shared] = i;
        shared_g[n_shared] = j;
        ++n_shared;
      }
  if (n_shared == 0) return CGAL::do_intersect(triangle(m, f), triangle(m, g));
  if (n_shared == 3) return true;  // the same triangle twice
  // Local positions of f's and g's vertices that are not shared.
  const auto others = [&](const int* shared, int face, int out[2]) {
    int k = 0;
    for (int i = 0; i < 3; ++i)
      if (std::find(shared, shared + n_shared, i) == shared + n_shared) out[k++] = m.F(face, i);
  };
  if (n_shared == 2) {
    // The planes of f and g meet in the line ab unless they are the same plane; then they overlap
    // beyond ab iff c and d lie on the same side of ab (a fold).
    const Point a = point(m, m.F(f, shared_f[0])), b = point(m, m.F(f, shared_f[1]));
    int c[2], d[2];
    others(shared_f, f, c);
    others(shared_g, g, d);
    const Point pc = point(m, c[0]), pd = point(m, d[0]);
    if (CGAL::orientation(a, b, pc, pd) != CGAL::COPLANAR) return false;
    return CGAL::coplanar_orientation(a, b, pc, pd) == CGAL::POSITIVE;
  }
  // One shared vertex v: t1 ∩ t2 ⊋ {v} iff the edge of one opposite v meets the other. (The convex set
  // t1 ∩ t2 holds [v, x] for some x ≠ v; the ray v→x leaves t1 through edge ab and t2 through cd, and
  // whichever exit comes first lies in the other triangle. The converse holds since v ∉ ab, cd.)
  int ab[2], cd[2];
  others(shared_f, f, ab);
  others(shared_g, g, cd);
  return CGAL::do_intersect(Segment(point(m, ab[0]), point(m, ab[1])), triangle(m, g)) ||
         CGAL::do_intersect(Segment(point(m, cd[0]), point(m, cd[1])), triangle(m, f));
}

}  // namespace

std::optional<std::pair<int, int>> find_self_intersection(const SurfaceMesh& mesh) {
  const int n_faces = static_cast<int>(mesh.F.rows());
  // CGAL's triangle tests require non-degenerate triangles; a degenerate one is reported as such.
  for (int f = 0; f < n_faces; ++f)
    if (CGAL::collinear(point(mesh, mesh.F(f, 0)), point(mesh, mesh.F(f, 1)), point(mesh, mesh.F(f, 2))))
      return std::make_pair(f, f);
  std::vector<Box> boxes;
  boxes.reserve(static_cast<size_t>(n_faces));
  for (int f = 0; f < n_faces; ++f) boxes.emplace_back(face_box(mesh, f), f);
  std::optional<std::pair<int, int>> first;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& p, const Box& q) {
    const std::pair<int, int> pair(std::min(p.info(), q.info()), std::max(p.info(), q.info()));
    if (first && *first <= pair) return;  // keep the smallest pair, independent of visiting order
    if (faces_intersect(mesh, pair.first, pair.second)) first = pair;
  });
  return first;
}

void check_not_self_intersecting(const SurfaceMesh& mesh, const std::string& what) {
  const auto pair = find_self_intersection(mesh);
  if (!pair) return;
  const auto face = [&](int f) {
    return "face " + std::to_string(f) + " (" + std::to_string(mesh.F(f, 0)) + ", " + std::to_string(mesh.F(f, 1)) +
           ", " + std::to_string(mesh.F(f, 2)) + ")";
  };
  if (pair->first == pair->second)
    throw std::runtime_error(what + ": " + face(pair->first) + " is degenerate (collinear vertices)");
  throw std::runtime_error(what + ": the surface intersects itself: " + face(pair->first) + " and " +
                           face(pair->second) + " intersect");
}

namespace {

CGAL::Bbox_3 overlap_region(const CGAL::Bbox_3& a, const CGAL::Bbox_3& b) {
  return CGAL::Bbox_3(std::max(a.xmin(), b.xmin()), std::max(a.ymin(), b.ymin()), std::max(a.zmin(), b.zmin()),
                      std::min(a.xmax(), b.xmax()), std::min(a.ymax(), b.ymax()), std::min(a.zmax(), b.zmax()));
}

/// The smallest (face_a, face_b) of two surfaces whose triangles intersect, among faces whose boxes
/// reach into `region` (the overlap of the surfaces' boxes).
std::optional<std::pair<int, int>> first_hit(const SurfaceMesh& a, const std::vector<CGAL::Bbox_3>& boxes_a,
                                             const SurfaceMesh& b, const std::vector<CGAL::Bbox_3>& boxes_b,
                                             const CGAL::Bbox_3& region) {
  std::vector<Box> near_a, near_b;
  for (int f = 0; f < static_cast<int>(boxes_a.size()); ++f)
    if (CGAL::do_overlap(boxes_a[f], region)) near_a.emplace_back(boxes_a[f], f);
  for (int f = 0; f < static_cast<int>(boxes_b.size()); ++f)
    if (CGAL::do_overlap(boxes_b[f], region)) near_b.emplace_back(boxes_b[f], f);
  std::optional<std::pair<int, int>> first;
  const auto test = [&](const Box& p, const Box& q) {
    const std::pair<int, int> candidate(p.info(), q.info());
    if (first && *first <= candidate) return;
    if (CGAL::do_intersect(triangle(a, p.info()), triangle(b, q.info()))) first = candidate;
  };
  // Small pairs (the usual case: two bodies resting on each other) are cheaper without the tree.
  if (near_a.size() * near_b.size() <= 4096) {
    for (const Box& p : near_a)
      for (const Box& q : near_b)
        if (CGAL::do_overlap(p.bbox(), q.bbox())) test(p, q);
  } else {
    CGAL::box_intersection_d(near_a.begin(), near_a.end(), near_b.begin(), near_b.end(), test);
  }
  return first;
}

}  // namespace

std::optional<TriangleIntersection> find_intersection(const std::vector<SurfaceMesh>& surfaces) {
  const int n = static_cast<int>(surfaces.size());
  std::vector<std::vector<CGAL::Bbox_3>> face_boxes(surfaces.size());
  std::vector<Box> surface_boxes;
  surface_boxes.reserve(surfaces.size());
  for (int s = 0; s < n; ++s) {
    if (surfaces[s].F.rows() == 0) continue;
    CGAL::Bbox_3 box;
    for (int f = 0; f < static_cast<int>(surfaces[s].F.rows()); ++f) {
      face_boxes[s].push_back(face_box(surfaces[s], f));
      box += face_boxes[s].back();
    }
    surface_boxes.emplace_back(box, s);
  }
  std::vector<std::pair<int, int>> pairs;  // surfaces whose boxes overlap, smaller index first
  CGAL::box_self_intersection_d(surface_boxes.begin(), surface_boxes.end(), [&](const Box& p, const Box& q) {
    pairs.emplace_back(std::min(p.info(), q.info()), std::max(p.info(), q.info()));
  });
  std::sort(pairs.begin(), pairs.end());
  std::vector<CGAL::Bbox_3> box_of(surfaces.size());
  for (const Box& b : surface_boxes) box_of[b.info()] = b.bbox();
  // In sorted order the first pair with a hit holds the smallest (surface_a, surface_b, face_a, face_b).
  for (const auto& [a, b] : pairs)
    if (const auto hit = first_hit(surfaces[a], face_boxes[a], surfaces[b], face_boxes[b],
                                   overlap_region(box_of[a], box_of[b])))
      return TriangleIntersection{a, hit->first, b, hit->second};
  return std::nullopt;
}

namespace {

/// One vertex and the bounding box of each connected component (by shared vertices) of a surface.
struct Component {
  int vertex;
  CGAL::Bbox_3 box;
};

std::vector<Component> components(const SurfaceMesh& m) {
  std::vector<int> parent(static_cast<size_t>(m.V.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int k = 1; k < 3; ++k) parent[root(m.F(f, k))] = root(m.F(f, 0));
  std::map<int, Component> by_root;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    auto [it, inserted] = by_root.try_emplace(root(m.F(f, 0)), Component{m.F(f, 0), CGAL::Bbox_3()});
    it->second.box += face_box(m, static_cast<int>(f));
  }
  std::vector<Component> out;
  for (const auto& [r, c] : by_root) out.push_back(c);
  return out;
}

using CgalMesh = CGAL::Surface_mesh<Point>;
using SideOf = CGAL::Side_of_triangle_mesh<CgalMesh, K>;

/// A closed surface converted to CGAL, with its point-location structure (an AABB tree).
struct Solid {
  CgalMesh mesh;
  std::unique_ptr<SideOf> side;
};

std::unique_ptr<Solid> make_solid(const SurfaceMesh& m, int index) {
  auto solid = std::make_unique<Solid>();
  std::vector<CgalMesh::Vertex_index> v;
  v.reserve(static_cast<size_t>(m.V.rows()));
  for (int i = 0; i < static_cast<int>(m.V.rows()); ++i) v.push_back(solid->mesh.add_vertex(point(m, i)));
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    if (solid->mesh.add_face(v[m.F(f, 0)], v[m.F(f, 1)], v[m.F(f, 2)]) == CgalMesh::null_face())
      throw std::runtime_error("find_containment: surface " + std::to_string(index) + " face " + std::to_string(f) +
                               " cannot be added to a manifold mesh (run check_closed_manifold first)");
  solid->side = std::make_unique<SideOf>(solid->mesh);
  return solid;
}

}  // namespace

std::optional<SurfaceContainment> find_containment(const std::vector<SurfaceMesh>& surfaces) {
  const int n = static_cast<int>(surfaces.size());
  std::vector<Box> surface_boxes;
  for (int s = 0; s < n; ++s)
    if (surfaces[s].F.rows() > 0) surface_boxes.emplace_back(surface_box(surfaces[s]), s);
  std::vector<CGAL::Bbox_3> box_of(surfaces.size());
  for (const Box& b : surface_boxes) box_of[b.info()] = b.bbox();
  // (inner, outer) pairs whose boxes nest: the only ones where containment is possible.
  std::vector<std::pair<int, int>> candidates;
  CGAL::box_self_intersection_d(surface_boxes.begin(), surface_boxes.end(), [&](const Box& p, const Box& q) {
    candidates.emplace_back(p.info(), q.info());
    candidates.emplace_back(q.info(), p.info());
  });
  std::sort(candidates.begin(), candidates.end());
  std::vector<std::unique_ptr<Solid>> solids(surfaces.size());
  std::vector<std::vector<Component>> parts(surfaces.size());
  std::vector<bool> have_parts(surfaces.size(), false);
  for (const auto& [inner, outer] : candidates) {
    if (!have_parts[inner]) {
      parts[inner] = components(surfaces[inner]);
      have_parts[inner] = true;
    }
    for (const Component& c : parts[inner]) {
      if (!contains(box_of[outer], c.box)) continue;
      if (!solids[outer]) solids[outer] = make_solid(surfaces[outer], outer);
      if ((*solids[outer]->side)(point(surfaces[inner], c.vertex)) == CGAL::ON_BOUNDED_SIDE)
        return SurfaceContainment{inner, c.vertex, outer};
    }
  }
  return std::nullopt;
}

}  // namespace stiffsoft
