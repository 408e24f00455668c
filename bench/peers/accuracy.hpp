#pragma once
/// @file Accuracy side by side: what each engine's run did to the geometry.
///
/// Checked for every engine the same way, on the stiffsoft surfaces placed at the engine's
/// poses (x = A x̄ + p), on frames every 1/check_fps s of simulated time and on the last:
/// - exact intersection of the triangles of different bodies (meshing/find_intersection,
///   CGAL exact predicates: what `stiffsoft check` runs);
/// - overlap depth: the deepest a vertex of one body lies inside another body, measured to the
///   nearest face plane of the convex piece that holds it (a convex body is one piece, a faceted
///   torus one piece per slice; bodies of neither kind are not measured). A lower bound on the
///   penetration depth (an edge can cut into a body with no vertex inside);
/// - tunnelling: an overlap deeper than half the thickness of the thinner of the two bodies, a
///   dynamic body's centre of mass below the top of the ground (the fixed body with the largest
///   x–z footprint) within its footprint, or two chain links whose centre lines were linked at
///   t = 0 and no longer are (linking number);
/// and, after every step, the deepest penetration the engine's own contacts reported (Bullet:
/// manifold distances, less the margins it adds; MuJoCo: contact dist), as the engine sees it.

#include <limits>
#include <string>
#include <vector>

#include "peers/engine.hpp"
#include "peers/peer_scene.hpp"

namespace stiffsoft::peers {

/// What the checks found over one run.
struct AccuracyReport {
  int frames_checked = 0;            ///< frames checked
  int frames_intersecting = 0;       ///< of which had a pair of intersecting triangles of different bodies
  std::string first_intersection;    ///< "t = T s: A / B ..." of the first such frame
  double max_overlap = 0;            ///< deepest vertex of one body inside another on a checked frame (m)
  std::string max_overlap_where;     ///< "A in B at t = T s"
  double max_engine_depth = 0;       ///< deepest penetration of the surfaces the engine reported (m)
  std::string engine_depth_where;    ///< "A / B at t = T s"
  int tunnelling_events = 0;         ///< checked frames with a tunnelling finding
  bool tunnelled = false;            ///< tunnelling_events > 0
  std::string tunnel_note;           ///< the first tunnelling finding, in words
  double smallest_distance = std::numeric_limits<double>::infinity();  ///< stiffsoft: smallest contact distance (m)
};

/// Collects the checks of one run.
class AccuracyMonitor {
 public:
  /// Prepares per-body convex pieces and the initial linking numbers of the scene's chain links.
  explicit AccuracyMonitor(const PeerScene& scene);
  /// Records the contacts an engine reported with overlap at time t (s).
  void contacts(const std::vector<Penetration>& penetrations, double t);
  /// Records stiffsoft's smallest contact distance of a step (m).
  void distance(double smallest_distance);
  /// Runs the frame checks on the engine's current poses at time t (s).
  void frame(const Engine& engine, double t);
  /// The findings so far.
  const AccuracyReport& report() const { return m_report; }

 private:
  /// A convex piece of a body: face planes (n, n·a) in the body frame; `outer` planes are
  /// the body's surface (depth is measured to them), the others cut pieces apart.
  struct Piece {
    std::vector<Eigen::Vector4d> planes;  ///< n·x ≤ d inside
    std::vector<bool> outer;              ///< plane is part of the body's surface
  };
  void tunnel(const std::string& what, double t);
  /// Depth (m, > 0) of the body-frame point inside the body, 0 when outside.
  double depth(int body, const Eigen::Vector3d& local) const;

  const PeerScene& m_scene;
  AccuracyReport m_report;
  std::vector<std::vector<Piece>> m_pieces;  ///< per body
  std::vector<int> m_linking;                ///< initial linking number of each linked pair
  bool m_tunnelled_this_frame = false;
};

}  // namespace stiffsoft::peers
