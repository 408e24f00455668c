#pragma once
/// @file Projected Newton with a CCD-bounded backtracking line search that accepts only
/// decreasing energy (IPC, Li et al. 2020, Alg. 1; ABD, Lan et al. 2022, Alg. 1).

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <stiffsoft/coupling/joints/reduced_basis.hpp>
#include <stiffsoft/coupling/linear_solver/forcing_term.hpp>
#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>
#include <stiffsoft/coupling/model/block_hessian.hpp>
#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/coupling/solver/phase_times.hpp>
#include <stiffsoft/coupling/solver/trial_path.hpp>
#include <stiffsoft/coupling/terms/energy_term.hpp>

namespace stiffsoft {

struct NewtonIterate;

/// Newton's stopping rule and limits.
struct NewtonSettings {
  double tolerance = 1e-2;   ///< ε_d (m/s): stop when max_k ‖(Φp)_k‖ / h < ε_d
  /// ... and when p changes no active contact's distance d by more than this fraction of d.
  double gap_tolerance = 0.2;
  /// ... and, where finite, when p moves no friction stencil in its stick zone by more than
  /// this fraction of ε_v h (EnergyTerm::stick_zone_step); infinite: no such condition.
  double stick_tolerance = std::numeric_limits<double>::infinity();
  double h = 1e-2;           ///< time step (s), to turn the step into a speed
  /// β h² (s²): the potentials' factor in the minimised energy ½ ‖q − q̃‖²_M + β h² V, to weigh
  /// the orthogonality energy a cut geodesic trial adds (TrialPath::chord_stretch, in J) against
  /// the direction's decrease; 1 where the terms are minimised as they are.
  double potential_scale = 1;
  int max_iterations = 200;  ///< cap on iterations
  int max_line_search = 60;  ///< cap on line-search trials per direction
  /// Line-search trials turn affine bodies along the rotation group (TrialPath); false: along
  /// the straight line q + α p. Ignored with joints' eliminated equalities, which are linear in q.
  bool geodesic_line_search = true;
  /// Each island of DOF blocks that no term couples on the move (EnergyTerm::join_coupled_blocks)
  /// is cut to its own CCD bound, so that an impact in one island does not shorten the others'
  /// steps; false: one bound for all.
  bool island_line_search = true;
  /// A direction whose first trial CCD cuts is solved again with a one-sided spring on the gap
  /// of each pair it found entering d̂ (EnteringSprings); false: taken as it is.
  bool entering_springs = true;
  ForcingTermSettings forcing;  ///< relative tolerances of Krylov solves (inexact Newton)
  /// DOF blocks held where they are (prescribed motion already in place): their gradient rows
  /// and off-diagonal Hessian blocks are dropped and every direction is zero on them.
  std::vector<int> held_blocks;
  /// Called with every direction, after its CCD bound and before its line search; for
  /// diagnostics (tools/newton_probe.cpp). It may evaluate the terms elsewhere but must leave
  /// them updated at the iterate. Empty: not called.
  std::function<void(const NewtonIterate&)> observer;
};

/// One Newton iterate and its direction, as NewtonSettings::observer sees it.
struct NewtonIterate {
  const Model& model;                      ///< the model
  const std::vector<EnergyTerm*>& terms;   ///< the minimised terms, updated at c
  const Configuration& c;                  ///< the iterate
  int iteration;                           ///< 0 for the minimisation's first direction
  double energy;                           ///< E(q)
  const Eigen::VectorXd& g;                ///< ∇E(q) (held blocks zeroed)
  const BlockHessian& H;                   ///< the matrix p was solved with (revised if a term revised it; without the springs, if any)
  const Eigen::VectorXd& p;                ///< the direction
  double alpha;                            ///< the CCD bound of the first trial, ≤ 1 (the smallest island's): along p, or along the chord to the geodesic path's end (TrialPath)
  std::size_t springs;                     ///< entering springs p was solved with (EnteringSprings); 0: p solves H p = −g
};

/// What one minimisation did.
struct NewtonReport {
  bool converged = false;        ///< the stopping rule was met
  int iterations = 0;            ///< Newton iterations (linear solves)
  int line_search_steps = 0;     ///< energy evaluations in line searches
  int line_search_halvings = 0;  ///< times the line search halved its step (a geodesic trial's straight retry at the same α is not one)
  double smallest_ccd_step = 1;  ///< smallest α bound returned by CCD
  int ccd_limited_iterations = 0;  ///< iterations whose CCD bound α was < 1
  int revised_directions = 0;      ///< directions solved again after a term revised its Hessian (friction)
  int entering_directions = 0;     ///< directions solved again with springs on pairs entering d̂ (EnteringSprings)
  double energy = 0;             ///< E at the result
  double last_step_speed = 0;    ///< max surface step / h of the last direction (m/s)
  int linear_iterations = 0;     ///< Krylov iterations summed over the linear solves (0 for direct solvers)
  int linear_fallbacks = 0;      ///< linear solves whose primary method failed and a fallback solved
  std::string linear_failure;    ///< the first linear-solve failure ("iteration k: …"), empty if none
  std::string failure;           ///< why it stopped without converging
};

/// Adds a later minimisation of the same step to `total`: counts add up, the smallest CCD step
/// is the smaller one, and the outcome (converged, energy, last step speed, failure) is `next`'s.
void accumulate(NewtonReport& total, const NewtonReport& next);

/// The straight line search's multiple of p for each island (bound: its CCD bounds, slope: gᵀp
/// over its blocks), from α: min(bound_i, α), or where those would not descend (Σ_i multiple_i
/// slope_i ≥ 0) the smallest of them for every island. Each island's part of an exact Newton
/// direction descends; an inexact solve's or the entering springs' need not, and halving
/// multiples that ascend never lowers E (docs/newton.md, session 50).
std::vector<double> island_multiples(const std::vector<double>& bound, double alpha, const std::vector<double>& slope);

/// Minimises Σ terms over q, starting from (and overwriting) q. Terms get update() at every
/// configuration they are evaluated at. With an iterative linear solver the Krylov tolerance
/// of each solve follows Eisenstat–Walker's forcing terms (linear_solver/forcing_term.hpp);
/// the stopping rule stays the one above (step size and contact gaps).
///
/// With a reduced basis q = N z + q_p (joints' linear equalities, joints/reduced_basis.hpp),
/// q must satisfy the equalities on entry; each direction solves (Nᵀ H N) dz = −Nᵀ g and steps
/// along p = N dz, so every iterate keeps them (to round-off). The line search, CCD and the
/// stopping rule are unchanged. Krylov backends are not supported with a basis (their DOF
/// blocks do not survive the elimination): std::invalid_argument. Held blocks with a basis must
/// hold every block its equalities tie to theirs (a sleeping joint group, Sleeping): the reduced
/// system then decouples them, and their directions are zero.
///
/// `hessian`, over model.blocks, keeps the Hessian's storage from call to call (a Simulation
/// keeps one for its run), so that blocks stored before need not be made again (null: a new
/// one for this call). Its contents do not change the result.
NewtonReport newton_minimize(const Model& model, const std::vector<EnergyTerm*>& terms,
                             Eigen::VectorXd& q, LinearSolver& solver, const NewtonSettings& settings,
                             PhaseTimes& times, const ReducedBasis* basis = nullptr,
                             BlockHessian* hessian = nullptr);

}  // namespace stiffsoft
