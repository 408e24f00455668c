#pragma once
/// @file Accuracy side by side: what each engine's run did to the geometry.
///
/// Checked for every engine the same way, on the stiffsoft surfaces placed at the engine's
/// poses (x = A x̄ + p):
/// - exact intersection of the triangles of different bodies (meshing/find_intersection,
///   CGAL exact predicates: `stiffsoft check`), on frames every 1/check_fps s and the last;
/// - tunnelling, on the same frames: a dynamic body's centre of mass inside another body, or
///   below the top of the ground (the fixed body with the largest x–z footprint) within its
///   footprint, or a chain link whose centre line is no longer linked with a link it was
///   linked with at t = 0 (linking number changed);
/// - the engines' own contacts after every step: the deepest penetration the engine reports,
///   and contacts whose surface depth exceeds half the thickness of the thinner of the two
///   bodies (interpenetration: also counted as tunnelling).

#include <limits>
#include <string>
#include <vector>

#include "peers/engine.hpp"
#include "peers/peer_scene.hpp"

namespace stiffsoft::peers {

/// What the checks found over one run.
struct AccuracyReport {
  int frames_checked = 0;            ///< frames tested for intersecting triangles
  int frames_intersecting = 0;       ///< of which had a pair of intersecting triangles of different bodies
  std::string first_intersection;    ///< "t = T s: A / B" of the first such frame
  double max_engine_depth = 0;       ///< deepest penetration the engine reported (m), its own shapes
  double max_surface_depth = 0;      ///< the same, of the bodies' surfaces (engine depth − margins) (m)
  std::string deepest_pair;          ///< "A / B at t = T s" of the deepest surface penetration
  int deep_contacts = 0;             ///< contacts deeper than half the thinner body's thickness
  int tunnelling_events = 0;         ///< frames with a body inside another, through the ground, or a link undone
  bool tunnelled = false;            ///< deep_contacts > 0 or tunnelling_events > 0
  std::string tunnel_note;           ///< the first tunnelling event, in words
  double smallest_distance = std::numeric_limits<double>::infinity();  ///< stiffsoft: smallest contact distance (m)
};

/// Collects the checks of one run.
class AccuracyMonitor {
 public:
  /// Prepares per-body planes and the initial linking numbers of the scene's chain links.
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
  void tunnel(const std::string& what, double t);
  bool inside(int body, const Pose& pose, const Eigen::Vector3d& x) const;

  const PeerScene& m_scene;
  AccuracyReport m_report;
  std::vector<std::vector<Eigen::Vector4d>> m_planes;  ///< per body, per convex piece, face planes (n, n·a), body frame
  std::vector<std::vector<int>> m_piece_begin;         ///< per body, first plane of each convex piece (+ end)
  std::vector<int> m_linking;                          ///< initial linking number of each linked pair
  bool m_tunnelled_this_frame = false;
};

}  // namespace stiffsoft::peers
