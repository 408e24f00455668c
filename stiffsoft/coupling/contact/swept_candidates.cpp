#include <stiffsoft/coupling/contact/swept_candidates.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <stiffsoft/coupling/for_each_item.hpp>

namespace stiffsoft {

namespace {
/// Segments on which more bodies left their boxes are not served (extension() stops looking):
/// bodies that move that much are rarely all alone, and a pile in motion pays a Newton
/// iteration beside which a new broad phase is small.
constexpr std::size_t kMostMovedBodies = 8;
/// Bodies per task when every vertex is checked against its box: a seed pile's body has about 20
/// vertices, a few ns each, and a task's hand-out costs a few µs.
constexpr std::size_t kBodyGrain = 64;
/// advance() finds the pairs of at most this share of the bodies (and at least kMostMovedBodies)
/// again; beyond it a new broad phase is no dearer.
constexpr std::size_t kAdvancedShare = 8;
}  // namespace

SweptCandidates::SweptCandidates(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                                 double proximity, double slack, double tight_slack, BroadPhase& finder)
    : m_lo(x0.array().min(x1.array())),
      m_hi(x0.array().max(x1.array())),
      m_slack(slack),
      m_inflation(proximity + slack + tight_slack) {
  if (!(tight_slack >= 0 && slack >= 0))
    throw std::invalid_argument("SweptCandidates: slack and tight_slack must be ≥ 0, got " + std::to_string(slack) +
                                " and " + std::to_string(tight_slack));
  m_all = finder.find(model, x0, x1, m_inflation, {{m_inflation, &m_ccd}, {slack, &m_tight}}, &m_region);
}

bool SweptCandidates::inside(const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, Eigen::Index first,
                             Eigen::Index count) const {
  const auto in = [&](const Eigen::MatrixX3d& x) {
    return (x.middleRows(first, count).array() >= m_lo.middleRows(first, count) - m_slack).all() &&
           (x.middleRows(first, count).array() <= m_hi.middleRows(first, count) + m_slack).all();
  };
  return in(x0) && in(x1);
}

bool SweptCandidates::covers(const Eigen::MatrixX3d& x) const {
  if (x.rows() != m_lo.rows()) return false;
  // By ranges of points in parallel: every trial of the line search asks.
  return tbb::parallel_reduce(
      tbb::blocked_range<Eigen::Index>(0, x.rows(), 4096), true,
      [&](const tbb::blocked_range<Eigen::Index>& r, bool inside) {
        const Eigen::Index begin = r.begin(), n = r.end() - r.begin();
        return inside && (x.middleRows(begin, n).array() >= m_lo.middleRows(begin, n) - m_slack).all() &&
               (x.middleRows(begin, n).array() <= m_hi.middleRows(begin, n) + m_slack).all();
      },
      [](bool a, bool b) { return a && b; });
}

std::optional<std::vector<int>> SweptCandidates::extension(const Model& model, const Eigen::MatrixX3d& x0,
                                                           const Eigen::MatrixX3d& x1) const {
  if (x0.rows() != m_lo.rows() || x1.rows() != m_lo.rows()) return std::nullopt;
  // Vertices within the slack of their bodies' regions come closer than 2·proximity only where
  // the regions, grown as all()'s boxes, meet. A moved body's region is its box on the
  // segment; it must meet no other body's, moved or not.
  const auto meets_another = [&](int b, const AxisBox& grown, const std::vector<AxisBox>& region) {
    for (std::size_t o = 0; o < region.size(); ++o)
      if (o != std::size_t(b) && grown.overlaps(region[o])) return true;
    return false;
  };
  // A body that moved mostly moved all its vertices: its first vertex tells, for a fraction of
  // the cost of all of them, when too many moved or one moved next to another body (a landing).
  std::size_t first_vertices_out = 0;
  for (int b = 0; b < int(model.bodies.size()); ++b) {
    const BodyModel& body = model.bodies[std::size_t(b)];
    if (body.vertex_end == body.vertex_begin || inside(x0, x1, body.vertex_begin, 1)) continue;
    if (++first_vertices_out > kMostMovedBodies || body.self_contact() ||
        meets_another(b, grown_segment_box(body, x0, x1), m_region))
      return std::nullopt;
  }
  const std::vector<char> out = bodies_out(model, x0, x1);
  std::vector<int> moved;
  std::vector<AxisBox> region = m_region;
  for (int b = 0; b < int(model.bodies.size()); ++b) {
    const BodyModel& body = model.bodies[std::size_t(b)];
    if (!out[std::size_t(b)]) continue;
    if (moved.size() == kMostMovedBodies || body.self_contact()) return std::nullopt;
    moved.push_back(b);
    region[std::size_t(b)] = grown_segment_box(body, x0, x1);
  }
  for (int b : moved)
    if (meets_another(b, region[std::size_t(b)], region)) return std::nullopt;
  return moved;
}

std::vector<char> SweptCandidates::bodies_out(const Model& model, const Eigen::MatrixX3d& x0,
                                              const Eigen::MatrixX3d& x1) const {
  // Every vertex, body by body in parallel (all of a pile's bodies, every line-search trial).
  std::vector<char> out(model.bodies.size());
  for_each_item(model.bodies.size(), kBodyGrain, [&](std::size_t b) {
    const BodyModel& body = model.bodies[b];
    const Eigen::Index count = body.vertex_end - body.vertex_begin;
    out[b] = count > 0 && !inside(x0, x1, body.vertex_begin, count);
  });
  return out;
}

std::vector<double> SweptCandidates::reach_from(const Eigen::MatrixX3d& x) const {
  std::vector<double> reach(std::size_t(x.rows()));
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    reach[std::size_t(v)] = (x.row(v).array() - (m_lo.row(v) - m_slack))
                                .max((m_hi.row(v) + m_slack) - x.row(v).array())
                                .matrix()
                                .norm();
  return reach;
}

void SweptCandidates::keep_near(const Model& model, Candidates near, const std::vector<double>& reach) {
  m_near = std::move(near);
  m_pending.reset();
  m_body_reach.assign(model.bodies.size(), 0.0);
  for (std::size_t v = 0; v < reach.size(); ++v) {
    double& r = m_body_reach[std::size_t(model.mesh.vertex_body[v])];
    r = std::max(r, reach[v]);
  }
}

void SweptCandidates::add_near(const Model& model, const Candidates& near, const std::vector<double>& reach) {
  if (!m_near || !m_pending) throw std::logic_error("SweptCandidates::add_near: no pairs pending");
  m_near->append(near);
  // The pending pairs' vertices were sorted out with these reaches: their bodies' bound them too.
  const CollisionMesh& mesh = model.mesh;
  const auto bound = [&](int v) {
    double& r = m_body_reach[std::size_t(mesh.vertex_body[std::size_t(v)])];
    r = std::max(r, reach[std::size_t(v)]);
  };
  for (const auto& [v, f] : m_pending->vertex_face)
    for (int u : {v, mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)}) bound(u);
  for (const auto& [ea, eb] : m_pending->edge_edge)
    for (int u : {mesh.E(ea, 0), mesh.E(ea, 1), mesh.E(eb, 0), mesh.E(eb, 1)}) bound(u);
  m_pending.reset();
}

void SweptCandidates::extend(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                             const std::vector<int>& moved) {
  if (!moved.empty()) {  // its reaches were those of the moved bodies' old boxes
    m_near.reset();
    m_pending.reset();
  }
  move_boxes(model, x0, x1, moved);
}

bool SweptCandidates::advance(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1) {
  if (x0.rows() != m_lo.rows() || x1.rows() != m_lo.rows()) return false;
  const std::size_t most = std::max(kMostMovedBodies, model.bodies.size() / kAdvancedShare);
  const std::vector<char> out = bodies_out(model, x0, x1);
  std::vector<int> moved;
  for (int b = 0; b < int(model.bodies.size()); ++b) {
    if (!out[std::size_t(b)]) continue;
    if (moved.size() == most || model.bodies[std::size_t(b)].self_contact()) return false;
    moved.push_back(b);
  }
  // The other bodies' vertices lie within the slack of their boxes, so a pair of theirs whose
  // boxes on the segment overlap grown by d̂/2 + tight_slack (tight()) or not grown (for_ccd())
  // has its kept boxes overlap grown by that plus the slack: it is one of all()'s. The moved
  // bodies' pairs, found at their new boxes and the others' kept ones, hold theirs likewise.
  move_boxes(model, x0, x1, moved);
  if (!moved.empty()) {
    const CollisionMesh& mesh = model.mesh;
    std::vector<char> is_moved(model.bodies.size(), 0);
    for (int b : moved) is_moved[std::size_t(b)] = 1;
    const auto moved_body = [&](const std::vector<int>& body_of, int primitive) {
      return is_moved[std::size_t(body_of[std::size_t(primitive)])] != 0;
    };
    const auto of_moved_vertex_face = [&](const std::array<int, 2>& p) {
      return moved_body(mesh.vertex_body, p[0]) || moved_body(mesh.face_body, p[1]);
    };
    const auto of_moved_edge_edge = [&](const std::array<int, 2>& p) {
      return moved_body(mesh.edge_body, p[0]) || moved_body(mesh.edge_body, p[1]);
    };
    const auto drop_moved = [&](Candidates& c) {  // the others in their order
      c.vertex_face.erase(std::remove_if(c.vertex_face.begin(), c.vertex_face.end(), of_moved_vertex_face),
                          c.vertex_face.end());
      c.edge_edge.erase(std::remove_if(c.edge_edge.begin(), c.edge_edge.end(), of_moved_edge_edge),
                        c.edge_edge.end());
    };
    Candidates found = pairs_of_bodies(model, m_lo, m_hi, m_inflation, m_region, moved);
    drop_moved(m_all);
    m_all.append(found);
    // Without near candidates yet, the first build sorts out all() anyway.
    if (m_near) {
      drop_moved(*m_near);
      if (m_pending) drop_moved(*m_pending);
      else m_pending.emplace();
      m_pending->append(found);
    }
  }
  keep_shrunk(model, x0, x1, m_inflation, m_all, {{m_inflation, &m_ccd}, {m_slack, &m_tight}});
  return true;
}

void SweptCandidates::move_boxes(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                                 const std::vector<int>& moved) {
  for (int b : moved) {
    const BodyModel& body = model.bodies[std::size_t(b)];
    const Eigen::Index first = body.vertex_begin, count = body.vertex_end - body.vertex_begin;
    m_lo.middleRows(first, count) = x0.middleRows(first, count).array().min(x1.middleRows(first, count).array());
    m_hi.middleRows(first, count) = x0.middleRows(first, count).array().max(x1.middleRows(first, count).array());
    m_region[std::size_t(b)] = grown_segment_box(body, x0, x1);
  }
}

AxisBox SweptCandidates::grown_segment_box(const BodyModel& body, const Eigen::MatrixX3d& x0,
                                           const Eigen::MatrixX3d& x1) const {
  const Eigen::Index first = body.vertex_begin, count = body.vertex_end - body.vertex_begin;
  const auto a = x0.middleRows(first, count).array(), b = x1.middleRows(first, count).array();
  return AxisBox(a.min(b).colwise().minCoeff().transpose() - m_inflation,
                 a.max(b).colwise().maxCoeff().transpose() + m_inflation);
}

}  // namespace stiffsoft
