#include <stiffsoft/coupling/contact/constraint_set.hpp>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace stiffsoft {

using contact::PrimitivePair;

namespace {

/// Canonical vertex order so that the same physical pair found from different candidates
/// compares equal: VV sorted, EV with its edge sorted, EE with each edge sorted and the
/// edges ordered, FV as the face stores it; its distance √d2.
ContactConstraint canonical(PrimitivePair kind, std::array<int, 4> v, double eps_x, bool segment, double d2) {
  switch (kind) {
    case PrimitivePair::VertexVertex:
      if (v[0] > v[1]) std::swap(v[0], v[1]);
      v[2] = v[3] = -1;
      break;
    case PrimitivePair::EdgeVertex:
      if (v[1] > v[2]) std::swap(v[1], v[2]);
      v[3] = -1;
      break;
    case PrimitivePair::EdgeEdge:
      if (v[0] > v[1]) std::swap(v[0], v[1]);
      if (v[2] > v[3]) std::swap(v[2], v[3]);
      if (std::make_pair(v[0], v[1]) > std::make_pair(v[2], v[3])) {
        std::swap(v[0], v[2]);
        std::swap(v[1], v[3]);
      }
      break;
    case PrimitivePair::FaceVertex: break;
  }
  ContactConstraint c;
  c.stencil.kind = kind;
  c.stencil.eps_x = kind == PrimitivePair::EdgeEdge ? eps_x : 0.0;
  c.stencil.segment_distance = segment;
  c.vertices = v;
  c.distance = std::sqrt(d2);
  return c;
}

std::array<int, 4> pick(const std::array<int, 4>& candidate, const contact::Classified& c) {
  std::array<int, 4> v{-1, -1, -1, -1};
  for (int i = 0; i < 4; ++i)
    if (c.local[i] >= 0) v[i] = candidate[c.local[i]];
  return v;
}

/// Vertices below this index fit a sort key's 30 bits (with −1, unused, as 0).
constexpr int kKeyedVertices = (1 << 30) - 1;

/// The order of the kind, then the four vertices, as a pair of integers: the kind and the first
/// two vertices + 1, then the last two, 30 bits each. Equal keys, the same contact.
using SortKey = std::pair<std::uint64_t, std::uint64_t>;
SortKey sort_key(const ContactConstraint& c) {
  const auto v = [&](int i) { return std::uint64_t(c.vertices[std::size_t(i)] + 1); };
  return {(std::uint64_t(c.stencil.kind) << 60) | (v(0) << 30) | v(1), (v(2) << 30) | v(3)};
}

}  // namespace

std::vector<ContactConstraint> build_constraints(const Model& model, const Eigen::MatrixX3d& x_by_column,
                                                 const Candidates& candidates, double dhat,
                                                 const NearCandidates* sort_out) {
  const CollisionMesh& mesh = model.mesh;
  if (x_by_column.rows() > kKeyedVertices)
    throw std::length_error("build_constraints: " + std::to_string(x_by_column.rows()) +
                            " surface vertices, more than the contacts' sort keys hold (" +
                            std::to_string(kKeyedVertices) + ")");
  const PointRows x = x_by_column;  // each candidate reads its points from four places, not twelve
  const double dhat2 = dhat * dhat;
  // Rounding margin of the bounds' comparisons: far above their rounding, so the set is the one
  // classification alone gives.
  constexpr double kMargin = 1e-6;
  const double cut = (1 + kMargin) * dhat2;
  tbb::enumerable_thread_specific<std::vector<ContactConstraint>> local;
  // With sort_out: 1 for the candidates that can come within d̂ in the reaches.
  std::vector<char> vertex_face_near(sort_out ? candidates.vertex_face.size() : 0),
      edge_edge_near(sort_out ? candidates.edge_edge.size() : 0);
  // The squared distance below which a pair of primitives, whose vertices move at most ra and
  // rb, may come closer than d̂.
  const auto near_limit = [&](double ra, double rb) {
    const double d = (1 + kMargin) * (dhat + (ra + rb) * (1 + kMargin));
    return d * d;
  };
  const auto reach = [&](std::initializer_list<int> vertices) {
    double r = 0;
    for (int v : vertices) r = std::max(r, sort_out->reach[std::size_t(v)]);
    return r;
  };

  tbb::parallel_for(size_t(0), candidates.vertex_face.size(), [&](size_t k) {
    const auto [v, f] = candidates.vertex_face[k];
    const std::array<int, 4> ids{v, mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
    const contact::Vector12d xs = gather(x, ids);
    // As for edge pairs below: far points are rejected by the plane's distance first.
    const double bound = contact::point_triangle_squared_distance_lower_bound(xs.segment<3>(0), xs.segment<3>(3),
                                                                              xs.segment<3>(6), xs.segment<3>(9));
    if (sort_out && bound <= near_limit(reach({ids[0]}), reach({ids[1], ids[2], ids[3]}))) vertex_face_near[k] = 1;
    if (bound > cut) return;
    const contact::Classified c = contact::classify_point_triangle(
        xs.segment<3>(0), xs.segment<3>(3), xs.segment<3>(6), xs.segment<3>(9));
    const double d2 = contact::squared_distance(c.kind, contact::gather_classified(c, xs));
    if (d2 < dhat2) local.local().push_back(canonical(c.kind, pick(ids, c), 0.0, false, d2));
  });

  tbb::parallel_for(size_t(0), candidates.edge_edge.size(), [&](size_t k) {
    const auto [ea, eb] = candidates.edge_edge[k];
    const std::array<int, 4> ids{mesh.E(ea, 0), mesh.E(ea, 1), mesh.E(eb, 0), mesh.E(eb, 1)};
    const contact::Vector12d xs = gather(x, ids);
    // Most candidates of resting piles are far: rejected by the cheap bounds first (the lines'
    // distance, then the segments' distances to each other's lines).
    const double lines = contact::line_line_squared_distance_lower_bound(xs.segment<3>(0), xs.segment<3>(3),
                                                                         xs.segment<3>(6), xs.segment<3>(9));
    double segments = -1;  // computed when needed
    const auto segment_bound = [&] {
      if (segments < 0)
        segments = contact::segment_segment_squared_distance_lower_bound(xs.segment<3>(0), xs.segment<3>(3),
                                                                          xs.segment<3>(6), xs.segment<3>(9));
      return segments;
    };
    if (sort_out) {
      const double limit = near_limit(reach({ids[0], ids[1]}), reach({ids[2], ids[3]}));
      if (lines <= limit && segment_bound() <= limit) edge_edge_near[k] = 1;
    }
    if (lines > cut || segment_bound() > cut) return;
    const contact::Classified c = contact::classify_edge_edge_stencil(xs);
    const double d2 = contact::squared_distance(c.kind, contact::gather_classified(c, xs));
    if (d2 >= dhat2) return;
    // Rest edge lengths are those of the body frame: affine bodies stay (nearly) rigid.
    const double eps_x = contact::edge_edge_mollifier_threshold(
        mesh.x_bar.row(ids[0]).transpose(), mesh.x_bar.row(ids[1]).transpose(),
        mesh.x_bar.row(ids[2]).transpose(), mesh.x_bar.row(ids[3]).transpose());
    if (contact::edge_edge_cross_squared_norm(xs) < eps_x)
      local.local().push_back(canonical(PrimitivePair::EdgeEdge, ids, eps_x, true, d2));
    else
      local.local().push_back(canonical(c.kind, pick(ids, c), eps_x, false, d2));
  });

  if (sort_out) {
    Candidates& near = sort_out->near;
    near.vertex_face.clear();
    near.edge_edge.clear();
    for (std::size_t k = 0; k < vertex_face_near.size(); ++k)
      if (vertex_face_near[k]) near.vertex_face.push_back(candidates.vertex_face[k]);
    for (std::size_t k = 0; k < edge_edge_near.size(); ++k)
      if (edge_edge_near[k]) near.edge_edge.push_back(candidates.edge_edge[k]);
  }

  std::size_t count = 0;
  for (const auto& l : local) count += l.size();
  std::vector<ContactConstraint> found;
  found.reserve(count);
  for (const auto& l : local) found.insert(found.end(), l.begin(), l.end());
  // Sorted by their keys with their places (integers compare in a fraction of the time the
  // constraints' fields take). Constraints with equal keys differ only in their weights, integer
  // multiplicities summed exactly below, and in the last bits of their distances, of which the
  // smallest is kept: the merged list is the same whatever the order among them.
  std::vector<std::pair<SortKey, std::uint32_t>> order(found.size());
  for (std::size_t k = 0; k < found.size(); ++k) order[k] = {sort_key(found[k]), std::uint32_t(k)};
  tbb::parallel_sort(order.begin(), order.end());
  std::vector<ContactConstraint> all;
  all.reserve(found.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const ContactConstraint& c = found[order[k].second];
    if (k > 0 && order[k].first == order[k - 1].first) {
      all.back().weight += c.weight;
      all.back().distance = std::min(all.back().distance, c.distance);
    } else {
      all.push_back(c);
    }
  }
  return all;
}

double smallest_distance(const Model& model, const Eigen::MatrixX3d& x, const Candidates& candidates) {
  const CollisionMesh& mesh = model.mesh;
  double d2 = std::numeric_limits<double>::infinity();
  for (const auto& [v, f] : candidates.vertex_face)
    d2 = std::min(d2, contact::point_triangle_squared_distance(
                          x.row(v).transpose(), x.row(mesh.F(f, 0)).transpose(),
                          x.row(mesh.F(f, 1)).transpose(), x.row(mesh.F(f, 2)).transpose()));
  for (const auto& [ea, eb] : candidates.edge_edge)
    d2 = std::min(d2, contact::segment_segment_squared_distance(
                          x.row(mesh.E(ea, 0)).transpose(), x.row(mesh.E(ea, 1)).transpose(),
                          x.row(mesh.E(eb, 0)).transpose(), x.row(mesh.E(eb, 1)).transpose()));
  return std::sqrt(d2);
}

}  // namespace stiffsoft
