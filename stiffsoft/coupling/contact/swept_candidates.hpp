#pragma once
/// @file One broad phase per Newton iteration instead of one per line-search trial: the
/// candidates of the swept boxes x → x + Δx, grown by d̂/2 plus a slack, hold every pair that
/// can come within d̂ anywhere on that segment (and slightly off it), so the line search's
/// trials and the CCD bound of the same direction reuse them (IPC's use of the CCD broad
/// phase). A configuration that strays from the segment falls back to a fresh broad phase.
/// A later segment that keeps every body within the slack of its boxes, or moves only bodies
/// that stay alone, is served by the same candidates (extension(); a resting pile's moves); one
/// that moves a few bodies next to others, by finding their pairs alone (advance()).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include <stiffsoft/coupling/contact/broad_phase.hpp>
#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// Candidates of one Newton direction, with the region they are valid in.
class SweptCandidates {
 public:
  /// Broad phase of the segment x0 → x1 (|V|×3, m), every box grown by proximity + slack +
  /// tight_slack (m): pairs closer than 2·proximity at any configuration whose vertices lie
  /// within `slack` of their own swept boxes are candidates. tight() holds the candidates whose
  /// boxes overlap grown by proximity + tight_slack only (the growth beyond the slack lets
  /// advance() find them among all()). `finder` is the run's broad phase.
  SweptCandidates(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, double proximity,
                  double slack, double tight_slack, BroadPhase& finder);
  /// True when every vertex of x (|V|×3, m) lies within the slack of its swept box, so the
  /// candidates hold every pair of x closer than 2·proximity.
  bool covers(const Eigen::MatrixX3d& x) const;
  /// Whether the candidates can serve the segment x0 → x1 (|V|×3, m) as well, without a new
  /// broad phase: every body either lies, at both ends, within the slack of its vertices'
  /// boxes (its pairs are already here), or is an affine body whose boxes on the segment,
  /// grown as all()'s boxes, come near no other body's (it has no pair). Returns those
  /// moved bodies (none, often) for extend(); nullopt when the segment is not served (a soft
  /// body left its boxes, a moved body came near another, or more than a few bodies moved).
  std::optional<std::vector<int>> extension(const Model& model, const Eigen::MatrixX3d& x0,
                                            const Eigen::MatrixX3d& x1) const;
  /// Serves the segment x0 → x1 that extension() accepted, which returned `moved`: their
  /// vertices' boxes become those of the segment, so covers() holds on it. for_ccd() stays
  /// the last swept or advanced segment's: an extended segment needs no CCD only when no pair of all() can
  /// close its gap on it (ClearMotion), for which the caller answers.
  void extend(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, const std::vector<int>& moved);
  /// Serves the segment x0 → x1 (|V|×3, m) where at most a few bodies, none with self-contact,
  /// leave their vertices' boxes: their boxes become those of the segment and their pairs are
  /// found again (pairs_of_bodies), the other bodies keep theirs, and for_ccd() and tight()
  /// become this segment's own, kept from all() by a fresh broad phase's box test: the sets a
  /// new SweptCandidates of the segment would hold. The near candidates among the other bodies
  /// stay; the moved bodies' new pairs wait in pending() to be sorted out. False, changing
  /// nothing, where more bodies moved (a new broad phase then costs no more).
  bool advance(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1);
  /// Every candidate (a superset of the proximity pairs of a covered configuration).
  const Candidates& all() const { return m_all; }
  /// Per surface vertex, how far from x (|V|×3, m, covered) it can be at any covered
  /// configuration (m): to the farthest corner of its swept box grown by the slack.
  std::vector<double> reach_from(const Eigen::MatrixX3d& x) const;
  /// The candidates of all() that can come within d̂ at a covered configuration, once
  /// keep_near() gave them (build_constraints over reach_from(); a resting pile's few percent);
  /// null before, after extend() moved a body, and while pending() holds pairs.
  const Candidates* near() const { return m_near && !m_pending ? &*m_near : nullptr; }
  /// The pairs advance() found for its moved bodies, where the near candidates of the others
  /// are kept: add_near() completes near() with those of them that are near; null otherwise.
  const Candidates* pending() const { return m_pending ? &*m_pending : nullptr; }
  /// Adds the near ones of pending(), sorted out at a covered configuration with these reaches
  /// (one per surface vertex).
  void add_near(const Model& model, const Candidates& near, const std::vector<double>& reach);
  /// Per body, the largest reach its vertices' pairs were sorted out with for near() (m): how
  /// far its vertices go within their boxes from where they were sorted out.
  const std::vector<double>& body_reach() const { return m_body_reach; }
  /// Keeps the near candidates found at a covered configuration with these reaches (NearCandidates).
  void keep_near(const Model& model, Candidates near, const std::vector<double>& reach);
  /// The candidates whose swept boxes overlap without any growth, for the CCD of the segment (the
  /// first, or the last advanced): what broad_phase(model, x0, x1, 0) finds, found in the same
  /// pass as all() (BroadPhase::find) or among all() by advance().
  const Candidates& for_ccd() const { return m_ccd; }
  /// The candidates whose swept boxes on the segment (the first, or the last advanced) overlap
  /// grown by proximity plus the constructor's `tight_slack`, found as for_ccd() is.
  const Candidates& tight() const { return m_tight; }

 private:
  /// The box of the body's (non-empty) vertices on the segment x0 → x1, grown as all()'s boxes.
  AxisBox grown_segment_box(const BodyModel& body, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1) const;
  /// Whether the rows [first, first + count) of x0 and x1 lie within the slack of their boxes.
  bool inside(const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, Eigen::Index first, Eigen::Index count) const;
  /// Per body, whether some vertex of it leaves the slack of its box at x0 or x1 (inside()).
  std::vector<char> bodies_out(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1) const;
  /// Makes the moved bodies' vertices' boxes and regions those of the segment x0 → x1.
  void move_boxes(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, const std::vector<int>& moved);

  /// Per-vertex swept box (no growth), for covers(): stored as x is, column by column.
  Eigen::ArrayX3d m_lo, m_hi;
  /// Per body, the box of its vertices' boxes grown by m_inflation (the broad phase's).
  std::vector<AxisBox> m_region;
  double m_slack;              ///< allowed distance of a covered configuration from the swept boxes (m)
  double m_inflation;          ///< growth of all()'s boxes: proximity + slack + tight_slack (m)
  Candidates m_ccd;            ///< for_ccd(), filled by the broad phase that fills m_all, or by advance()
  Candidates m_tight;          ///< tight(), likewise
  Candidates m_all;
  std::optional<Candidates> m_near;     ///< near() (without pending() while it holds pairs)
  std::optional<Candidates> m_pending;  ///< pending()
  std::vector<double> m_body_reach;     ///< body_reach()
};

}  // namespace stiffsoft
