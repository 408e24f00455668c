#pragma once
/// @file Time stepping of a model: one incremental-potential minimisation per step.

#include <memory>
#include <optional>
#include <string>

#include "coupling/integrator.hpp"
#include "coupling/linear_solver/linear_solver.hpp"
#include "coupling/model.hpp"
#include "coupling/newton.hpp"
#include "coupling/terms/barrier_term.hpp"
#include "coupling/terms/elasticity_term.hpp"
#include "coupling/terms/friction_term.hpp"
#include "coupling/terms/inertia_term.hpp"
#include "coupling/terms/orthogonality_term.hpp"

namespace stiffsoft {

/// Everything that drives the time stepping, in SI units, already resolved (no relative
/// defaults left: the scene loader turns those into numbers).
struct SimulationSettings {
  double h = 1e-2;                                ///< time step (s)
  Integrator integrator = Integrator::BackwardEuler;
  Eigen::Vector3d gravity{0, -9.81, 0};           ///< m/s²
  double dhat = 1e-3;                             ///< barrier activation distance d̂ (m)
  double mu = 0;                                  ///< friction coefficient; 0: no friction term at all
  double eps_v = 1e-3;                            ///< friction smoothing speed ε_v (m/s)
  std::optional<double> kappa;                    ///< fixed barrier stiffness; unset: adaptive
  double tolerance = 1e-2;                        ///< Newton's ε_d (m/s)
  int max_iterations = 200;                       ///< Newton iteration cap per step
  std::string linear_solver = "cholmod";          ///< linear solver backend
  double kinematic_weight = 1e4;                  ///< inertia weight pulling kinematic bodies onto their path
};

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
  double kappa = 0;              ///< barrier stiffness at the end of the step
  PhaseTimes times;              ///< seconds per phase
  double seconds = 0;            ///< wall time of the whole step (s)
};

/// A model advanced in time.
class Simulation {
 public:
  /// Starts at t = 0 in the model's initial configuration and velocities.
  Simulation(Model model, const SimulationSettings& settings);
  /// Advances by one step h.
  StepStats step();
  /// Simulated time (s).
  double time() const { return m_time; }
  /// The model.
  const Model& model() const { return m_model; }
  /// The settings.
  const SimulationSettings& settings() const { return m_settings; }
  /// DOFs q and velocities q̇.
  const Eigen::VectorXd& q() const { return m_q; }
  /// DOF velocities q̇.
  const Eigen::VectorXd& qdot() const { return m_qdot; }
  /// Surface positions, |V|×3 (m).
  Eigen::MatrixX3d surface() const { return m_model.surface(m_q); }
  /// Surface velocities Φ q̇, |V|×3 (m/s).
  Eigen::MatrixX3d surface_velocity() const { return m_model.surface_step(m_qdot); }
  /// Contact (barrier) force on each surface vertex at the end of the last step, |V|×3 (N).
  Eigen::MatrixX3d contact_forces() const;
  /// Friction force on each surface vertex over the last step, |V|×3 (N); zero without friction.
  Eigen::MatrixX3d friction_forces() const;
  /// Positions of the soft bodies' nodes, |N|×3 (m).
  Eigen::MatrixX3d node_positions() const { return m_model.node_positions(m_q); }
  /// Velocities of the soft bodies' nodes, |N|×3 (m/s): zero for fixed nodes.
  Eigen::MatrixX3d node_velocities() const;
  /// Von Mises stress of every soft tetrahedron (Model::nodes.T order), Pa; empty without soft bodies.
  Eigen::VectorXd von_mises() const;

 private:
  /// Newton's starting point: every dynamic body moved rigidly (p from q̃, A turned by
  /// exp([ω]× h)), kinematic bodies onto their target (q̃), as far along the straight line from
  /// qⁿ as CCD allows. Starting at qⁿ would make Newton turn a spinning body through linearised
  /// rotations, each of which stretches it against the stiff orthogonality potential.
  Eigen::VectorXd initial_guess(const Eigen::VectorXd& q_tilde, const Configuration& c_n) const;

  Model m_model;
  SimulationSettings m_settings;
  std::unique_ptr<LinearSolver> m_solver;
  PhaseTimes m_times;
  InertiaTerm m_inertia;
  OrthogonalityTerm m_orthogonality;
  ElasticityTerm m_elasticity;
  BarrierTerm m_barrier;
  std::optional<FrictionTerm> m_friction;
  Eigen::VectorXd m_q, m_qdot, m_q_prev, m_qdot_prev, m_gravity_q;
  double m_time = 0;
  int m_step = 0;
};

}  // namespace stiffsoft
