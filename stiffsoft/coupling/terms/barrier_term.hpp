#pragma once
/// @file κ Σ_k b(d_k(x), d̂): the IPC contact barrier over all active stencils (Li et al. 2020),
/// with CCD-bounded steps and IPC's adaptive barrier stiffness.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <stiffsoft/coupling/contact/barrier_potential.hpp>
#include <stiffsoft/coupling/contact/constraint_set.hpp>
#include <stiffsoft/coupling/solver/phase_times.hpp>
#include <stiffsoft/coupling/contact/swept_candidates.hpp>
#include <stiffsoft/coupling/model/stencil_jacobian.hpp>
#include <stiffsoft/coupling/terms/energy_term.hpp>

namespace stiffsoft {

/// Settings of the contact barrier.
struct BarrierSettings {
  double dhat = 1e-3;               ///< activation distance d̂ (m)
  std::optional<double> kappa;      ///< fixed barrier stiffness; unset: adaptive (IPC's rule)
  /// Adaptive κ only: balance it once, at the first contact, against the other terms' gradient
  /// (IPC's initial-stiffness formula, clamped to [κ_min, 100 κ_min]); false keeps κ_min and
  /// only doubles it when contacts come closer than 1e-9 × diagonal.
  bool balance = false;
  double bbox_diagonal = 1.0;       ///< scene size (m), for the adaptive rule's thresholds
  double average_mass = 1.0;        ///< average dynamic body mass (kg), for κ_min
  /// Newton's Hessian of each stencil (scene key solver.barrier_hessian).
  contact::BarrierHessian hessian = contact::BarrierHessian::Projected;
  /// The fraction of its Hessian Newton solves again with for a contact its direction releases,
  /// taking it 35–65 % of the rest of the way out of d̂ (scene key solver.release_hessian; 1: off).
  double release_hessian = 0.6;
};

/// The contact barrier term.
class BarrierTerm final : public EnergyTerm {
 public:
  /// `times` receives broad-phase and CCD seconds (may be null).
  BarrierTerm(const Model& model, const BarrierSettings& settings, PhaseTimes* times);
  /// See EnergyTerm::name.
  const char* name() const override { return "barrier"; }
  /// Rebuilds candidates and active contacts at c.x; nothing to do when c.x is, value for
  /// value, where they were last built (a step's result, then the next step's start) or in one
  /// of the two builds before (those contacts are kept).
  void update(const Configuration& c) override;
  /// See EnergyTerm::value.
  double value(const Configuration& c) const override;
  /// See EnergyTerm::add_gradient.
  void add_gradient(const Configuration& c, Eigen::VectorXd& g) const override;
  /// See EnergyTerm::add_hessian.
  void add_hessian(const Configuration& c, BlockHessian& H) const override;
  /// See EnergyTerm::revise_hessian: on every active contact the full step dx releases (takes
  /// 35–65 % of the rest of the way out of d̂), replaces its Hessian in H by
  /// BarrierSettings::release_hessian of it; true if any. Newton on the barrier's cubic tail
  /// takes an unloaded contact half of the rest of the way out per step; with 0.6 of the
  /// Hessian it takes it all but a sixth (docs/newton.md).
  bool revise_hessian(const Configuration& c, const Eigen::VectorXd& dq, const Eigen::MatrixX3d& dx,
                      BlockHessian& H) const override;
  /// Conservative CCD over the straight-line motion x → x + dx; its broad phase (grown by
  /// d̂/2) is kept for update() on the same segment. A move the kept candidates serve and on
  /// which none of their pairs can close its gap (keeps_clear) needs neither: 1.
  double max_step(const Configuration& c, const Eigen::VectorXd& dq, const Eigen::MatrixX3d& dx) const override;
  /// Joins the blocks of every candidate pair of the move's broad phase (grown by d̂/2, as
  /// max_step's): pairs outside it stay farther than d̂ apart along the whole move. Keeps that
  /// broad phase for max_step_per_island and update() (or those kept, as max_step does).
  void join_coupled_blocks(const Configuration& c, const Eigen::MatrixX3d& dx, BlockIslands& islands) const override;
  /// max_step's CCD on join_coupled_blocks' broad phase, each pair's time bounding its island.
  void max_step_per_island(const Configuration& c, const Eigen::VectorXd& dq, const Eigen::MatrixX3d& dx,
                           const BlockIslands& islands, std::vector<double>& bound) const override;
  /// The pairs farther than d̂ at c (so without a barrier term yet) whose CCD time on the move
  /// last bounded, as its max_step or max_step_per_island found it, fell below the bound its query
  /// looked up to (1 for a point–triangle pair, the island's point–triangle bound for an
  /// edge–edge pair); each with its gap's slack down to kEnteringGap d̂. None when the move was
  /// kept clear (keeps_clear). Pairs between affine and fixed bodies only: a spring holds only
  /// the soft node CCD found, and its neighbours hit next (a soft ball landing on boxes took 11
  /// cut directions and 16 iterations in one step with them, 3 and 6 without; docs/newton.md).
  void entering_pairs(const Configuration& c, std::vector<EnteringPair>& out) const override;
  /// The gap, as a fraction of d̂, down to which an entering pair's spring lets it close: inside
  /// the barrier's reach, so that the next direction's model has the pair (docs/newton.md,
  /// session 44: 0.5, 0.8 and 0.9 measured on medium and full at h = 1/240).
  static constexpr double kEnteringGap = 0.8;
  /// IPC's adaptive rule: double κ (up to κ_max) while the smallest distance keeps shrinking
  /// below 1e-9 × diagonal; true when κ changed.
  bool end_iteration(const Configuration& c) override;

  /// IPC's initial κ by gradient balancing, clamped to [κ_min, 100 κ_min]: κ = −∇E·∇B / ‖∇B‖²,
  /// where ∇E is the gradient of the other terms at the step's start. Acts once, at the first
  /// step that starts with active contacts; no-op with a fixed κ or without BarrierSettings::balance.
  void initialize_stiffness(const Configuration& c, const Eigen::VectorXd& grad_other);
  /// Current κ (J/m⁴ in squared-distance units, i.e. κ b has units of energy).
  double kappa() const { return m_kappa; }
  /// See EnergyTerm::relative_gap_change.
  double relative_gap_change(const Configuration& c, const Eigen::MatrixX3d& dx) const override;
  /// Whether initialize_stiffness has balanced κ already (it does so once per run).
  bool kappa_balanced() const { return m_balanced; }
  /// From the next build on, leaves out of the active contacts every stencil all of whose
  /// vertices are on bodies marked in `still` (one entry per body: sleeping and fixed bodies,
  /// Sleeping::still_bodies), whose distances cannot change while they stay still; forgets the
  /// kept builds when the marks change. Empty: none left out.
  void hold_still(const std::vector<char>& still);
  /// Continues a run from a saved κ and balance flag (Simulation::restore).
  void restore_stiffness(double kappa, bool balanced) {
    m_kappa = kappa;
    m_balanced = balanced;
  }
  /// Active contacts at the last update.
  const std::vector<ContactConstraint>& constraints() const { return m_constraints; }
  /// The DOF blocks' order in space for the owners' parts (blocks_along_widest_axis, at the
  /// last new build on two or more threads; empty before): friction's assembly cuts it too.
  const std::vector<int>& block_rank() const { return m_block_rank; }
  /// The number of the build constraints() come from: equal numbers, the same contacts at the
  /// same surface (a surface built again, or taken back from the kept builds, keeps its number).
  std::uint64_t build() const { return m_build; }
  /// Moves (max_step, join_coupled_blocks) served by the candidates kept from an earlier move,
  /// without a broad phase or a CCD query, because none of their pairs could close its gap.
  std::size_t kept_moves() const { return m_kept_moves; }
  /// Smallest distance among the active contacts of the last update, at c.x (m), +∞ with none.
  double min_active_distance(const Configuration& c) const;
  /// Barrier force −κ ∇_x B on every surface vertex, |V|×3 (in energy units; divide by β h² for N).
  Eigen::MatrixX3d vertex_forces(const Configuration& c) const;
  /// The activation distance d̂ (m).
  double dhat() const { return m_settings.dhat; }

 private:
  /// The CCD bound of the segment x0 → x1 over m_swept's candidates, for one island (`islands`
  /// null, `bound` of size 1) or for each.
  void ccd_bounds(const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, const BlockIslands* islands,
                  std::vector<double>& bound) const;
  /// The contacts at x, which m_swept covers, from its near candidates (sorted out at x first
  /// where it has none yet).
  std::vector<ContactConstraint> covered_constraints(const Eigen::MatrixX3d& x) const;
  /// The DOF blocks of active contact k's vertices (−1 for none), in the stencil's order.
  std::array<int, 4> stencil_blocks(size_t k) const;
  /// scale × stencil k's Newton Hessian at c, as blocks of J^T H J.
  void stencil_hessian(const Configuration& c, size_t k, double scale, StencilHessian& out) const;
  const Model& m_model;
  BarrierSettings m_settings;
  PhaseTimes* m_times;
  double m_kappa;
  double m_kappa_max;
  double m_prev_min_distance = -1;
  bool m_balanced = false;
  std::vector<ContactConstraint> m_constraints;
  Eigen::MatrixX3d m_constraints_at;  ///< the surface m_constraints were built at
  /// Builds before m_constraints that update() keeps (Newton's comparison of two full steps
  /// returns to the iterate after building at both).
  static constexpr std::size_t kKeptBuilds = 2;
  /// The contacts of the kKeptBuilds builds before m_constraints, most recent first, and where.
  std::array<std::vector<ContactConstraint>, kKeptBuilds> m_previous;
  std::array<Eigen::MatrixX3d, kKeptBuilds> m_previous_at;
  /// Whether m_constraints were built at the surface x (the same numbers).
  bool built_at(const Eigen::MatrixX3d& x) const { return m_constraints_at.rows() == x.rows() && m_constraints_at == x; }
  /// d² of every active contact at c.x, where they were built, and at c.x + dx when dx is
  /// given: computed once per build and move, and read by every pass over the contacts that
  /// needs them (value and add_gradient at c.x, revise_hessian, relative_gap_change,
  /// min_active_distance).
  const std::vector<double>& squared_distances(const Configuration& c, const Eigen::MatrixX3d* dx = nullptr) const;
  /// squared_distances' results: of which build, the move (none at c.x itself), the values.
  struct SquaredDistances {
    std::uint64_t build = 0;
    Eigen::MatrixX3d dx;
    std::vector<double> d2;
  };
  mutable std::array<SquaredDistances, 2> m_squared;  ///< [0]: at c.x, [1]: at c.x + dx
  std::uint64_t m_builds = 0;  ///< builds so far; each build's number identifies its contacts
  std::uint64_t m_build = 0;   ///< the number of m_constraints' build (0: none yet)
  std::array<std::uint64_t, kKeptBuilds> m_previous_build{};  ///< that of m_previous
  std::vector<int> m_vertex_block;  ///< vertex_block of each surface vertex
  std::vector<char> m_still_body;   ///< hold_still's marks (empty: none)
  /// The DOF blocks' order in space at the last new build on two or more threads, for the
  /// owners' parts (blocks_along_widest_axis): it shapes only who computes what.
  std::vector<int> m_block_rank;
  /// The run's broad phase, which remembers body pairs' primitive pairs between calls.
  mutable BroadPhase m_broad_phase;
  /// Whether the kept candidates also serve the move c.x → x1 (SweptCandidates::extension)
  /// and none of their pairs can close its clearance on it (ClearMotion, with the active set
  /// at c.x): then every CCD query of the move would return 1, so neither a broad phase nor a
  /// query is needed (the step's first move in a resting pile). Extends them to the move.
  bool keeps_clear(const Configuration& c, const Eigen::MatrixX3d& x1) const;
  /// Makes m_swept the candidates of the move c.x → x1: the kept ones advanced to it where they
  /// can be (SweptCandidates::advance), else a new swept broad phase.
  void sweep(const Configuration& c, const Eigen::MatrixX3d& x1) const;
  /// Candidates of the last direction max_step bounded, reused by update() on that segment.
  mutable std::optional<SweptCandidates> m_swept;
  /// Whether join_coupled_blocks' move was one keeps_clear() kept, for max_step_per_island.
  mutable bool m_move_clear = false;
  /// A candidate pair whose CCD time on the last bounded move fell below the bound its query
  /// looked up to (entering_pairs).
  struct CutPair {
    std::array<int, 4> vertices;  ///< the pair's stencil vertices
    bool vertex_face;             ///< point–triangle, else edge–edge
  };
  mutable std::vector<CutPair> m_cut;
  mutable std::size_t m_kept_moves = 0;  ///< kept_moves()
};

}  // namespace stiffsoft
