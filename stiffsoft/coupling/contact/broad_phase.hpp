#pragma once
/// @file Broad phase: body pairs first (the seed's i-AABB culling: boxes of the transformed
/// bodies), then primitive pairs inside each overlapping body pair by sort-and-sweep, and those
/// of a soft body against itself through a uniform grid over the body.

#include <Eigen/Core>
#include <array>
#include <vector>

#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// Primitive pairs whose boxes overlap: between two different bodies, at least one of which
/// carries DOFs, or inside one soft body (self-contact) when they share no vertex.
struct Candidates {
  std::vector<std::array<int, 2>> vertex_face;  ///< (vertex, face)
  std::vector<std::array<int, 2>> edge_edge;    ///< (edge, edge), first < second
  /// Appends the pairs of `more` after this one's.
  void append(const Candidates& more) {
    vertex_face.insert(vertex_face.end(), more.vertex_face.begin(), more.vertex_face.end());
    edge_edge.insert(edge_edge.end(), more.edge_edge.begin(), more.edge_edge.end());
  }
};

/// Candidates for the motion of every surface vertex on the segment x0 → x1 (|V|×3 each, m):
/// a vertex's box spans both ends, grown by `inflation` (m) on every side. For proximity
/// (x1 = x0) an inflation of d̂/2 finds every pair closer than d̂. The pairs come body pair by
/// body pair, in an order fixed by the model and the boxes, not by the thread schedule.
Candidates broad_phase(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                       double inflation);

/// An axis-aligned box (m).
struct AxisBox {
  Eigen::Array3d lo, hi;
  /// Leaves lo and hi uninitialised: the broad phase resizes vectors of boxes and then fills
  /// them, and the zeroing an aggregate gets there was 1 % of a Newton iteration on full.
  AxisBox() {}
  /// The box [lo, hi].
  AxisBox(const Eigen::Array3d& lo, const Eigen::Array3d& hi) : lo(lo), hi(hi) {}
  /// Whether the boxes share a point (closed boxes).
  bool overlaps(const AxisBox& o) const { return (lo <= o.hi).all() && (o.lo <= hi).all(); }
  /// Whether `o` lies inside this box.
  bool contains(const AxisBox& o) const { return (lo <= o.lo).all() && (o.hi <= hi).all(); }
};

/// Pairs BroadPhase::find also writes, from the same pass: those whose boxes still overlap
/// shrunk by `shrink` (m, at most the inflation) on every side, i.e. broad_phase(model, x0, x1,
/// inflation − shrink)'s (and a few pairs whose boxes miss by less than 1e-9 · shrink).
struct ShrunkCandidates {
  double shrink;    ///< m
  Candidates* out;  ///< replaced by those pairs
};

/// Primitive pairs, as broad_phase() would consider them, between each body of `bodies` (without
/// self-contact) and every other body, a pair of two of them once, whose boxes overlap: a vertex's
/// box is its row of lo and hi (|V|×3, m) grown by `inflation` (m), and `body_box` holds each
/// body's box, the union of its vertices' (as BroadPhase::find's `body_boxes`). In the order of
/// `bodies`, then of the other body.
Candidates pairs_of_bodies(const Model& model, const Eigen::ArrayX3d& lo, const Eigen::ArrayX3d& hi,
                           double inflation, const std::vector<AxisBox>& body_box,
                           const std::vector<int>& bodies);

/// Fills each of `shrunk` with the pairs of `pairs` that BroadPhase::find(model, x0, x1,
/// inflation, shrunk) puts there (the same boxes and test), in the order of `pairs`: where
/// `pairs` holds every pair of those sets, exactly find()'s sets.
void keep_shrunk(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, double inflation,
                 const Candidates& pairs, const std::vector<ShrunkCandidates>& shrunk);

/// The broad phase of a run: the same candidates as broad_phase() at every call, found from
/// memory where the bodies barely moved (a Verlet list per body pair). Each body keeps
/// reference boxes, its vertices' boxes grown by `margin` when it last moved out of them; a
/// body pair's primitive pairs are found by sort-and-sweep of those reference boxes and kept
/// while neither body leaves them, and every call keeps those of its pairs whose current boxes
/// overlap. Exact: the current boxes lie inside the reference ones, so no overlapping pair is
/// missed. Pairs of kept body pairs come in the order they were found, so the order (not the
/// set) depends on the calls before; the contact set (sorted) and the CCD bound (a minimum)
/// do not.
class BroadPhase {
 public:
  /// `margin` (m): how far a body may move beyond the boxes of the call that last found its
  /// pairs before they are found again.
  explicit BroadPhase(double margin) : m_margin(margin) {}
  /// The candidates broad_phase(model, x0, x1, inflation) finds, as a set. With `shrunk` (at
  /// most kMostShrunk), also those of smaller growths (ShrunkCandidates), from the same pass:
  /// a shrink of `inflation` gives broad_phase(model, x0, x1, 0)'s. With `body_boxes`, each
  /// body's box there: the union of its vertices' boxes on the segment grown by `inflation`
  /// (one that meets nothing for a body without vertices).
  Candidates find(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, double inflation,
                  const std::vector<ShrunkCandidates>& shrunk = {}, std::vector<AxisBox>* body_boxes = nullptr);
  /// The most ShrunkCandidates one find() writes.
  static constexpr std::size_t kMostShrunk = 2;
  /// Body pairs of the last find() whose primitive pairs were found again (the others came from memory).
  std::size_t refreshed_pairs() const { return m_refreshed; }
  /// Body pairs of the last find().
  std::size_t body_pair_count() const { return m_pairs.size(); }

 private:
  /// One body pair's primitive pairs, found at the reference boxes of the given versions.
  struct PairCandidates {
    int a, b;
    unsigned version_a, version_b;
    Candidates pairs;
  };
  double m_margin;
  std::vector<AxisBox> m_vertex, m_face, m_edge, m_body;  ///< reference boxes
  std::vector<unsigned> m_version;                         ///< per body: its reference boxes' version
  std::vector<PairCandidates> m_pairs;                     ///< sorted by (a, b)
  std::size_t m_refreshed = 0;
};

}  // namespace stiffsoft
