#include "peers/accuracy.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>

#include "meshing/intersection.hpp"
#include "peers/ring_links.hpp"

namespace stiffsoft::peers {

namespace {

std::string at_time(double t) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "t = %.4g s", t);
  return buffer;
}

Eigen::Vector4d plane(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
  return {n.x(), n.y(), n.z(), n.dot(a)};
}

Eigen::MatrixX3d placed(const Eigen::MatrixX3d& local, const Pose& pose) {
  return (local * pose.A.transpose()).rowwise() + pose.p.transpose();
}

}  // namespace

AccuracyMonitor::AccuracyMonitor(const PeerScene& scene) : m_scene(scene) {
  for (const PeerBody& body : scene.bodies) {
    std::vector<Eigen::Vector4d> planes;
    std::vector<int> begin{0};
    if (body.torus) {
      // Slice j: its outer faces [2jm, 2(j+1)m) and the two cap planes through the tube's rings.
      const TorusFacets& t = *body.torus;
      for (int j = 0; j < t.n; ++j) {
        for (int f = 2 * j * t.m; f < 2 * (j + 1) * t.m; ++f)
          planes.push_back(plane(body.x_bar.row(body.F(f, 0)), body.x_bar.row(body.F(f, 1)), body.x_bar.row(body.F(f, 2))));
        const Eigen::MatrixX3d slice = torus_slice(body, j);
        for (int ring = 0; ring < 2; ++ring) {
          // The cap plane holds ring (j + ring); orient it away from the other ring.
          const Eigen::Vector3d a = slice.row(ring * t.m), b = slice.row(ring * t.m + 1), c = slice.row(ring * t.m + 2);
          Eigen::Vector4d cap = plane(a, b, c);
          const Eigen::Vector3d other = slice.row((1 - ring) * t.m);
          if (cap.head<3>().dot(other) - cap[3] > 0) cap = -cap;
          planes.push_back(cap);
        }
        begin.push_back(int(planes.size()));
      }
    } else if (body.convex) {
      for (Eigen::Index f = 0; f < body.F.rows(); ++f)
        planes.push_back(plane(body.x_bar.row(body.F(f, 0)), body.x_bar.row(body.F(f, 1)), body.x_bar.row(body.F(f, 2))));
      begin.push_back(int(planes.size()));
    }
    m_planes.push_back(std::move(planes));
    m_piece_begin.push_back(std::move(begin));
  }
  for (const auto& [i, j] : scene.linked_rings) {
    const PeerBody &a = scene.bodies[i], &b = scene.bodies[j];
    m_linking.push_back(linking_number(placed(torus_centre_line(a), {a.R0, a.c0}), placed(torus_centre_line(b), {b.R0, b.c0})));
  }
}

void AccuracyMonitor::contacts(const std::vector<Penetration>& penetrations, double t) {
  for (const Penetration& p : penetrations) {
    m_report.max_engine_depth = std::max(m_report.max_engine_depth, p.engine);
    if (p.surface > m_report.max_surface_depth) {
      m_report.max_surface_depth = p.surface;
      m_report.deepest_pair = m_scene.bodies[p.body_a].name + " / " + m_scene.bodies[p.body_b].name + " at " + at_time(t);
    }
    const double limit = 0.5 * std::min(m_scene.bodies[p.body_a].thickness, m_scene.bodies[p.body_b].thickness);
    if (p.surface > limit) {
      ++m_report.deep_contacts;
      if (!m_report.tunnelled) {
        char what[256];
        std::snprintf(what, sizeof what, "%s and %s overlap by %.3g m (> half the thinner body's thickness, %.3g m)",
                      m_scene.bodies[p.body_a].name.c_str(), m_scene.bodies[p.body_b].name.c_str(), p.surface, limit);
        m_report.tunnel_note = std::string(what) + " at " + at_time(t);
      }
      m_report.tunnelled = true;
    }
  }
}

void AccuracyMonitor::distance(double smallest_distance) {
  m_report.smallest_distance = std::min(m_report.smallest_distance, smallest_distance);
}

void AccuracyMonitor::tunnel(const std::string& what, double t) {
  if (!m_report.tunnelled) m_report.tunnel_note = what + " at " + at_time(t);
  m_report.tunnelled = true;
  m_tunnelled_this_frame = true;
}

bool AccuracyMonitor::inside(int body, const Pose& pose, const Eigen::Vector3d& x) const {
  const Eigen::Vector3d local = pose.A.inverse() * (x - pose.p);
  const std::vector<Eigen::Vector4d>& planes = m_planes[size_t(body)];
  const std::vector<int>& begin = m_piece_begin[size_t(body)];
  for (size_t piece = 0; piece + 1 < begin.size(); ++piece) {
    bool in = true;
    for (int k = begin[piece]; k < begin[piece + 1] && in; ++k) in = planes[size_t(k)].head<3>().dot(local) < planes[size_t(k)][3];
    if (in) return true;
  }
  return false;
}

void AccuracyMonitor::frame(const Engine& engine, double t) {
  const size_t n = m_scene.bodies.size();
  std::vector<SurfaceMesh> surfaces(n);
  std::vector<Pose> poses(n);
  std::vector<std::string> names(n);
  Eigen::MatrixX3d lo(n, 3), hi(n, 3);
  for (size_t b = 0; b < n; ++b) {
    poses[b] = engine.pose(int(b));
    surfaces[b] = {placed(m_scene.bodies[b].x_bar, poses[b]), m_scene.bodies[b].F};
    names[b] = m_scene.bodies[b].name;
    lo.row(Eigen::Index(b)) = surfaces[b].V.colwise().minCoeff();
    hi.row(Eigen::Index(b)) = surfaces[b].V.colwise().maxCoeff();
  }
  ++m_report.frames_checked;
  if (const auto hit = find_intersection(surfaces)) {
    if (m_report.frames_intersecting++ == 0) m_report.first_intersection = at_time(t) + ": " + describe(SurfaceOverlap(*hit), names);
  }

  m_tunnelled_this_frame = false;
  for (size_t a = 0; a < n; ++a) {
    if (m_scene.bodies[a].fixed) continue;
    const Eigen::Vector3d x = poses[a].p;
    for (size_t b = 0; b < n; ++b) {
      if (b == a || (x.transpose().array() < lo.row(Eigen::Index(b)).array()).any() ||
          (x.transpose().array() > hi.row(Eigen::Index(b)).array()).any())
        continue;
      if (inside(int(b), poses[b], x)) tunnel("the centre of mass of " + names[a] + " is inside " + names[b], t);
    }
    if (m_scene.ground >= 0) {
      const Eigen::Index g = m_scene.ground;
      if (x.y() < hi(g, 1) && x.x() > lo(g, 0) && x.x() < hi(g, 0) && x.z() > lo(g, 2) && x.z() < hi(g, 2))
        tunnel("the centre of mass of " + names[a] + " is below the top of " + names[size_t(g)], t);
    }
  }
  for (size_t k = 0; k < m_scene.linked_rings.size(); ++k) {
    const auto [i, j] = m_scene.linked_rings[k];
    const int now = linking_number(placed(torus_centre_line(m_scene.bodies[i]), poses[size_t(i)]),
                                   placed(torus_centre_line(m_scene.bodies[j]), poses[size_t(j)]));
    if (now != m_linking[k]) tunnel("links " + names[size_t(i)] + " and " + names[size_t(j)] + " came apart", t);
  }
  if (m_tunnelled_this_frame) ++m_report.tunnelling_events;
}

}  // namespace stiffsoft::peers
