#pragma once
/// @file What drives the time stepping of a Simulation, and the check that it makes sense.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include <stiffsoft/coupling/solver/integrator.hpp>
#include <stiffsoft/coupling/solver/newton.hpp>
#include <stiffsoft/coupling/terms/barrier_term.hpp>
#include <stiffsoft/coupling/terms/damping_term.hpp>

namespace stiffsoft {

/// With friction_iterations > 1, the fraction of ε_v to which a step resolves friction: Newton
/// does not stop while its last direction moves a sticking stencil by more than this fraction of
/// ε_v h (NewtonSettings::stick_tolerance), and friction is lagged again while the lag error
/// exceeds this fraction of ε_v (Simulation::step). Neither depends on Newton's ε_d.
inline constexpr double friction_resolution = 0.1;

/// Everything that drives the time stepping, in SI units, already resolved (no relative
/// defaults left: the scene loader turns those into numbers).
struct SimulationSettings {
  double h = NewtonSettings{}.h;                  ///< time step (s)
  Integrator integrator = Integrator::BackwardEuler;
  Eigen::Vector3d gravity{0, -9.81, 0};           ///< m/s²
  double dhat = 1e-3;                             ///< barrier activation distance d̂ (m)
  double mu = 0;                                  ///< friction coefficient; 0: no friction term at all
  double eps_v = 1e-3;                            ///< friction smoothing speed ε_v (m/s)
  std::optional<double> kappa;                    ///< fixed barrier stiffness; unset: adaptive
  bool balance_kappa = BarrierSettings{}.balance;  ///< adaptive κ: balance it once, at the first contact (BarrierSettings::balance)
  int friction_iterations = 1;                    ///< friction lags per step: at the start, then again while the lag error exceeds friction_resolution ε_v (Simulation::step)
  double tolerance = NewtonSettings{}.tolerance;  ///< Newton's ε_d (m/s)
  double gap_tolerance = NewtonSettings{}.gap_tolerance;  ///< Newton also needs every active contact's gap to change by at most this fraction
  int max_iterations = NewtonSettings{}.max_iterations;  ///< Newton iteration cap per solve (a step solves again per friction re-lag)
  contact::BarrierHessian barrier_hessian = BarrierSettings{}.hessian;  ///< Newton's Hessian of the barrier stencils
  double release_hessian = BarrierSettings{}.release_hessian;  ///< fraction of its Hessian a contact Newton releases keeps (BarrierSettings::release_hessian)
  bool geodesic_line_search = NewtonSettings{}.geodesic_line_search;  ///< line-search trials turn affine bodies along the rotation group (TrialPath)
  bool island_line_search = NewtonSettings{}.island_line_search;  ///< each island of uncoupled blocks its own CCD bound (BlockIslands)
  bool entering_springs = NewtonSettings{}.entering_springs;  ///< a direction CCD cuts is solved again with springs on the pairs entering d̂ (EnteringSprings)
  std::string linear_solver = "auto";             ///< linear solver backend (see make_linear_solver())
  double krylov_rtol_max = ForcingTermSettings{}.eta_max;  ///< largest relative residual a Krylov solve may stop at (η_max)
  double kinematic_weight = 1e4;                  ///< inertia weight pulling kinematic bodies onto their path where they cannot be held on it (see Simulation)
  double rigidity_bound = 1e-2;                   ///< largest rigidity error ‖AᵀA − I‖_F an affine body may reach (PhysicsError past it)
  double contact_damping = 0;                     ///< lagged Rayleigh damping k_d of contacts (s); 0: none
  std::vector<ContactPairDamping> contact_pair_damping;  ///< k_d per body pair, replacing contact_damping there
  double sleep_time = 0;                          ///< t_s: an affine body at rest this long, beside bodies at rest as long, sleeps (Sleeping, s); 0: none sleeps
  std::optional<double> sleep_speed;              ///< v_s: the speed below which a body rests (m/s); unset: the tolerance ε_d
};

/// Checks code-built settings as the scene loader checks a scene file: h, d̂, ε_v, ε_d, gap_tolerance,
/// kinematic_weight and rigidity_bound > 0 and finite, μ, contact damping and sleep_time ≥ 0, κ and sleep_speed > 0 when set,
/// max_iterations and friction_iterations ≥ 1, release_hessian in (0, 1], krylov_rtol_max in (0, 1), gravity finite, a known linear solver, pair
/// damping on bodies ≥ 0 with k_d ≥ 0. Throws std::invalid_argument naming the first bad
/// setting and what was expected (`SimulationSettings.dhat: must be > 0 (got -1)`).
void validate(const SimulationSettings& settings);

/// The barrier's settings in a simulation of `model`: d̂ and κ from the settings, the model's
/// bounding-box diagonal, and the average mass of what carries DOFs (dynamic affine bodies and
/// dynamic soft nodes, each one node of its mass, as IPC averages over nodes) for κ_min (and its balance).
BarrierSettings barrier_settings(const Model& model, const SimulationSettings& settings);

}  // namespace stiffsoft
