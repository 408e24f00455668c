#include "peers/accuracy.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cstdio>

#include <stiffsoft/meshing/intersection.hpp>
#include "peers/ring_links.hpp"

namespace stiffsoft::peers {

namespace {

std::string at_time(double t) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "t = %.4g s", t);
  return buffer;
}

std::string metres(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g m", x);
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
    std::vector<Piece> pieces;
    const auto face_plane = [&](Eigen::Index f) {
      return plane(body.x_bar.row(body.F(f, 0)), body.x_bar.row(body.F(f, 1)), body.x_bar.row(body.F(f, 2)));
    };
    if (body.torus) {
      // Slice j: its outer faces [2jm, 2(j+1)m) and the two cap planes through its rings.
      const TorusFacets& t = *body.torus;
      for (int j = 0; j < t.n; ++j) {
        Piece piece;
        for (int f = 2 * j * t.m; f < 2 * (j + 1) * t.m; ++f) {
          piece.planes.push_back(face_plane(f));
          piece.outer.push_back(true);
        }
        const Eigen::MatrixX3d slice = torus_slice(body, j);
        for (int ring = 0; ring < 2; ++ring) {
          const Eigen::Vector3d a = slice.row(ring * t.m), b = slice.row(ring * t.m + 1), c = slice.row(ring * t.m + 2);
          Eigen::Vector4d cap = plane(a, b, c);
          const Eigen::Vector3d other = slice.row((1 - ring) * t.m);
          if (cap.head<3>().dot(other) - cap[3] > 0) cap = -cap;  // the other ring is inside
          piece.planes.push_back(cap);
          piece.outer.push_back(false);
        }
        pieces.push_back(std::move(piece));
      }
    } else if (body.convex) {
      Piece piece;
      for (Eigen::Index f = 0; f < body.F.rows(); ++f) {
        piece.planes.push_back(face_plane(f));
        piece.outer.push_back(true);
      }
      pieces.push_back(std::move(piece));
    }
    m_pieces.push_back(std::move(pieces));
  }
  for (const auto& [i, j] : scene.linked_rings) {
    const PeerBody &a = scene.bodies[i], &b = scene.bodies[j];
    m_linking.push_back(
        linking_number(placed(torus_centre_line(a), {a.R0, a.c0}), placed(torus_centre_line(b), {b.R0, b.c0})));
  }
}

void AccuracyMonitor::contacts(const std::vector<Penetration>& penetrations, double t) {
  for (const Penetration& p : penetrations)
    if (p.surface > m_report.max_engine_depth) {
      m_report.max_engine_depth = p.surface;
      m_report.engine_depth_where =
          m_scene.bodies[p.body_a].name + " / " + m_scene.bodies[p.body_b].name + " at " + at_time(t);
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

double AccuracyMonitor::depth(int body, const Eigen::Vector3d& local) const {
  double deepest = 0;
  for (const Piece& piece : m_pieces[size_t(body)]) {
    double to_surface = std::numeric_limits<double>::infinity();
    bool inside = true;
    for (size_t k = 0; k < piece.planes.size() && inside; ++k) {
      const double gap = piece.planes[k][3] - piece.planes[k].head<3>().dot(local);  // > 0 inside
      inside = gap > 0;
      if (piece.outer[k]) to_surface = std::min(to_surface, gap);
    }
    if (inside) deepest = std::max(deepest, to_surface);
  }
  return deepest;
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
  if (const auto hit = find_intersection(surfaces))
    if (m_report.frames_intersecting++ == 0)
      m_report.first_intersection = at_time(t) + ": " + describe(SurfaceOverlap(*hit), names);

  m_tunnelled_this_frame = false;
  for (size_t a = 0; a < n; ++a) {
    const PeerBody& body_a = m_scene.bodies[a];
    for (size_t b = 0; b < n; ++b) {
      const PeerBody& body_b = m_scene.bodies[b];
      if (b == a || (body_a.fixed && body_b.fixed) || m_pieces[b].empty() ||
          (hi.row(Eigen::Index(a)).array() < lo.row(Eigen::Index(b)).array()).any() ||
          (lo.row(Eigen::Index(a)).array() > hi.row(Eigen::Index(b)).array()).any())
        continue;
      const Eigen::Matrix3d to_b = poses[b].A.inverse();
      double deepest = 0;
      for (Eigen::Index v = 0; v < surfaces[a].V.rows(); ++v)
        deepest = std::max(deepest, depth(int(b), to_b * (surfaces[a].V.row(v).transpose() - poses[b].p)));
      if (deepest > m_report.max_overlap) {
        m_report.max_overlap = deepest;
        m_report.max_overlap_where = names[a] + " in " + names[b] + " at " + at_time(t);
      }
      const double limit = 0.5 * std::min(body_a.thickness, body_b.thickness);
      if (deepest > limit)
        tunnel(names[a] + " is " + metres(deepest) + " deep in " + names[b] + " (more than half the thinner body's thickness, " +
                   metres(limit) + ")",
               t);
    }
    if (!body_a.fixed && m_scene.ground >= 0) {
      const Eigen::Vector3d x = poses[a].p;
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
