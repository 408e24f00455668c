#pragma once
/// @file What one time step did: StepStats, and its columns in `stats.csv` (defined here once,
/// each name beside its value).

#include <Eigen/Core>
#include <string>
#include <vector>

#include <stiffsoft/coupling/solver/newton.hpp>
#include <stiffsoft/coupling/solver/phase_times.hpp>

namespace stiffsoft {

/// What one step did (a row of stats.csv).
struct StepStats {
  int step = 0;                  ///< 1-based step index
  double time = 0;               ///< simulated time at the end of the step (s)
  NewtonReport newton;           ///< iterations, line search, convergence
  int contacts = 0;              ///< active contact stencils at the end of the step
  double smallest_distance = 0;  ///< smallest active contact distance (m), +∞ without contact
  double kinetic_energy = 0;     ///< ½ q̇ᵀ M q̇ of dynamic bodies (J)
  double potential_energy = 0;   ///< gravitational, −Σ m g·p (J)
  Eigen::Vector3d linear_momentum = Eigen::Vector3d::Zero();  ///< Σ m ṗ of dynamic bodies (kg·m/s)
  double orthogonality_error = 0;  ///< max_b ‖A_b A_bᵀ − I‖_F over dynamic affine bodies
  double elastic_energy = 0;     ///< Σ_e V_e ψ(F_e) of the soft bodies (J)
  int inverted_tets = 0;         ///< soft tetrahedra with det F ≤ 0 at the end of the step
  std::vector<int> inverted_per_body;  ///< the same per body, indexed like Model::bodies; empty without soft bodies
  int friction_relags = 0;       ///< times friction was lagged again within the step (contact.friction_iterations − 1 at most)
  /// Friction's lag error at the result: an estimate of the largest change of a dynamic body's
  /// mean velocity that friction lagged there would make against the lag the step was solved
  /// with (m/s; Simulation::friction_lag_error); 0 without friction.
  double friction_lag_error = 0;
  int sticking = 0;              ///< friction stencils (λ > 0) whose slide over the step is inside the stick zone ε_v h
  int sliding = 0;               ///< friction stencils whose slide over the step is outside it
  /// Changes of a friction stencil between sticking and sliding from one accepted Newton
  /// iterate to the next, summed over the stencils and the step's iterations
  int stick_slip_flips = 0;
  double kappa = 0;              ///< barrier stiffness at the end of the step
  double joint_error = 0;        ///< largest violation of the joints' linear equalities at the end of the step (m)
  double joint_force = 0;        ///< largest joint force magnitude at the end of the step (N), see Simulation::joint_forces()
  int sleeping_bodies = 0;       ///< bodies asleep at the end of the step (SimulationSettings::sleep_time)
  PhaseTimes times;              ///< seconds per phase
  double seconds = 0;            ///< wall time of the whole step (s)
};

/// One column of `stats.csv`: its header name and how a StepStats gives its value.
struct StepStatsColumn {
  const char* name;                     ///< header name, e.g. "newton_iterations"
  double (*value)(const StepStats& s);  ///< the column's value for one step
};

/// The columns of `stats.csv`, in file order.
const std::vector<StepStatsColumn>& step_stats_columns();

/// The header names of step_stats_columns(), in order.
std::vector<std::string> step_stats_column_names();

/// One step as a `stats.csv` row, in step_stats_columns() order.
std::vector<double> step_stats_row(const StepStats& s);

}  // namespace stiffsoft
