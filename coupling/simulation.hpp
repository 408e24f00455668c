#pragma once
/// @file Time stepping of a model: one incremental-potential minimisation per step.

#include <memory>
#include <optional>
#include <string>

#include "coupling/integrator.hpp"
#include "coupling/joints/linear_constraints.hpp"
#include "coupling/joints/reduced_basis.hpp"
#include "coupling/linear_solver/linear_solver.hpp"
#include "coupling/model.hpp"
#include "coupling/newton.hpp"
#include "coupling/terms/barrier_term.hpp"
#include "coupling/terms/damping_term.hpp"
#include "coupling/terms/elasticity_term.hpp"
#include "coupling/terms/friction_term.hpp"
#include "coupling/terms/inertia_term.hpp"
#include "coupling/terms/joint_term.hpp"
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
  std::string linear_solver = "auto";             ///< linear solver backend (see make_linear_solver())
  double krylov_rtol_max = ForcingTermSettings{}.eta_max;  ///< largest relative residual a Krylov solve may stop at (η_max)
  double kinematic_weight = 1e4;                  ///< inertia weight pulling kinematic bodies onto their path
  double contact_damping = 0;                     ///< lagged Rayleigh damping k_d of contacts (s); 0: none
  std::vector<ContactPairDamping> contact_pair_damping;  ///< k_d per body pair, replacing contact_damping there
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
  double joint_error = 0;        ///< largest violation of the joints' linear equalities at the end of the step (m)
  double joint_force = 0;        ///< largest joint force magnitude at the end of the step (N), see Simulation::joint_forces()
  PhaseTimes times;              ///< seconds per phase
  double seconds = 0;            ///< wall time of the whole step (s)
};

/// What changes from step to step: enough for another Simulation of the same model and
/// settings (its linear solver may differ) to continue the run exactly from here.
struct SimulationState {
  double time = 0;                          ///< simulated time (s)
  int step = 0;                             ///< steps taken
  Eigen::VectorXd q, qdot, q_prev, qdot_prev;  ///< DOFs and velocities now and one step back
  double kappa = 0;                         ///< the barrier's adaptive stiffness κ
  bool kappa_balanced = false;              ///< whether κ was balanced at first contact already
};

/// A model advanced in time.
class Simulation {
 public:
  /// Starts at t = 0 in the model's initial configuration and velocities.
  Simulation(Model model, const SimulationSettings& settings);
  /// Advances by one step h.
  StepStats step();
  /// The state now (a copy).
  SimulationState state() const;
  /// Continues from `s`, taken from a Simulation of the same model and settings;
  /// std::invalid_argument when its vectors do not match this model's DOFs.
  void restore(const SimulationState& s);
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
  /// The joints' linear equalities C q = d (no rows without linear joints).
  const LinearConstraints& joint_constraints() const { return m_constraints; }
  /// The change of variables that eliminates them; null without linear joints.
  const ReducedBasis* reduced_basis() const { return m_basis ? &*m_basis : nullptr; }
  /// The joints' penalties and limit barriers.
  const JointTerm& joint_term() const { return m_joints; }
  /// Force of each joint on its body a at the end of the last step, world frame (N), indexed
  /// like Model::joints: the multipliers of its eliminated point equalities (least squares
  /// from the step's optimality, ∇E = Cᵀ μ, force μ / (β h²)) plus its penalty and barrier
  /// forces. Torque-only parts (hinge ranges, prismatic orientation) are not included. Zero
  /// before the first step.
  const std::vector<Eigen::Vector3d>& joint_forces() const { return m_joint_forces; }
  /// World position of each joint's anchor on body a (m), indexed like Model::joints.
  std::vector<Eigen::Vector3d> joint_positions() const;
  /// World position of each joint's point on body b (m): its anchor on body b, soft node or
  /// world point (equal to joint_positions() for ball, cone-twist and hinge joints).
  std::vector<Eigen::Vector3d> joint_positions_b() const;
  /// Each joint's smallest gap to one of its limits now (rad or m, as the limit), NaN for a
  /// joint without limits; indexed like Model::joints.
  std::vector<double> joint_gaps() const;

 private:
  /// Newton's starting point: every dynamic body moved rigidly (p from q̃, A turned by
  /// exp([ω]× h)), kinematic bodies onto their target (q̃), as far along the straight line from
  /// qⁿ as CCD allows. Starting at qⁿ would make Newton turn a spinning body through linearised
  /// rotations, each of which stretches it against the stiff orthogonality potential.
  Eigen::VectorXd initial_guess(const Eigen::VectorXd& q_tilde, const Configuration& c_n) const;
  /// Fills m_joint_forces at the end of a step: `terms` are the step's energy terms, already
  /// updated at q.
  void compute_joint_forces(const std::vector<EnergyTerm*>& terms, const Configuration& c);

  Model m_model;
  SimulationSettings m_settings;
  std::unique_ptr<LinearSolver> m_solver;
  PhaseTimes m_times;
  InertiaTerm m_inertia;
  OrthogonalityTerm m_orthogonality;
  ElasticityTerm m_elasticity;
  BarrierTerm m_barrier;
  std::optional<FrictionTerm> m_friction;
  LinearConstraints m_constraints;
  std::optional<ReducedBasis> m_basis;
  JointTerm m_joints;
  DampingTerm m_damping;
  std::vector<Eigen::Vector3d> m_joint_forces;
  Eigen::VectorXd m_q, m_qdot, m_q_prev, m_qdot_prev, m_gravity_q;
  double m_time = 0;
  int m_step = 0;
};

}  // namespace stiffsoft
