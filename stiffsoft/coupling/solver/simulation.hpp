#pragma once
/// @file Time stepping of a model: one incremental-potential minimisation per step.

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <stiffsoft/coupling/solver/integrator.hpp>
#include <stiffsoft/coupling/joints/linear_constraints.hpp>
#include <stiffsoft/coupling/joints/reduced_basis.hpp>
#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>
#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/coupling/solver/newton.hpp>
#include <stiffsoft/coupling/solver/physics_error.hpp>
#include <stiffsoft/coupling/solver/simulation_settings.hpp>
#include <stiffsoft/coupling/solver/sleeping.hpp>
#include <stiffsoft/coupling/solver/step_stats.hpp>
#include <stiffsoft/coupling/terms/barrier_term.hpp>
#include <stiffsoft/coupling/terms/damping_term.hpp>
#include <stiffsoft/coupling/terms/elasticity_term.hpp>
#include <stiffsoft/coupling/terms/friction_term.hpp>
#include <stiffsoft/coupling/terms/inertia_term.hpp>
#include <stiffsoft/coupling/terms/joint_term.hpp>
#include <stiffsoft/coupling/terms/orthogonality_term.hpp>

namespace stiffsoft {

/// What changes from step to step: enough for another Simulation of the same model and
/// settings to continue the run exactly from here.
struct SimulationState {
  double time = 0;                          ///< simulated time (s)
  int step = 0;                             ///< steps taken
  Eigen::VectorXd q, qdot, q_prev, qdot_prev;  ///< DOFs and velocities now and one step back
  double kappa = 0;                         ///< the barrier's adaptive stiffness κ
  bool kappa_balanced = false;              ///< whether κ was balanced at first contact already
  LinearSolverMemory solver;                ///< the linear solver's choices so far ("auto"'s backend)
  Sleeping::State sleeping;                 ///< rest times and sleeping bodies (empty vectors when nothing may sleep)
};

/// A model advanced in time.
class Simulation {
 public:
  /// Starts at t = 0 in the model's initial configuration and velocities; checks the settings
  /// first (validate(), std::invalid_argument naming the setting).
  Simulation(Model model, const SimulationSettings& settings);
  /// Not copyable or movable: the energy terms hold references into the Simulation.
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;
  /// Advances by one step h. Kinematic bodies and prescribed soft nodes end the step exactly on
  /// their path; sleeping bodies (SimulationSettings::sleep_time) stay where they are. Throws PhysicsError (physics_error.hpp), leaving the state at the last step,
  /// when a prescribed motion cannot be followed without intersection or an affine body's
  /// rigidity error ‖AᵀA − I‖_F would exceed SimulationSettings::rigidity_bound.
  StepStats step();
  /// Calls `observer` with every Newton direction of the following steps (diagnostics, e.g.
  /// tools/newton_probe.cpp); an empty function stops it.
  void observe_newton(std::function<void(const NewtonIterate&)> observer) { m_newton_observer = std::move(observer); }
  /// The state now (a copy).
  SimulationState state() const;
  /// Continues from `s`, taken from a Simulation of the same model and settings;
  /// std::invalid_argument when its vectors do not match this model's DOFs. A state without
  /// sleeping bodies' data (empty vectors) wakes every body.
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
  /// Friction force on each surface vertex over the last step, |V|×3 (N); zero without friction
  /// and after a step in which every body slept (nothing slid).
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
  /// An estimate of friction's lag error at c (m/s): over the dynamic bodies, the largest change
  /// of a body's mean velocity that its friction would make if its normal forces were lagged at
  /// c instead, from the change of their sum over the stencils that touch it: c_v μ |Σ_k λ_k(c)
  /// − Σ_k λ_k(lagged)| / (h m_b), c_v from velocity_coefficient (λ in the incremental
  /// potential's units). Force moving between a body's contacts, turned tangent bases and
  /// torques are not seen; a soft body counts as its whole mass. c must be the barrier's
  /// current configuration (update() done). The friction term keeps the stencils it makes at c
  /// for the next lag there (the next step's).
  double friction_lag_error(const Configuration& c);
  /// One solve of the step from qⁿ (`c_n`) towards q̃: κ balanced, friction and damping lagged at
  /// c_n, Newton from initial_guess() with the sleeping bodies held (after waking those a
  /// predicted move reaches), friction lagged again at the result as the settings ask. Adds its
  /// counts to `stats`; `terms` and `held` get the energy terms and held DOF blocks it used.
  /// Returns q^{n+1}.
  Eigen::VectorXd solve_step(const Eigen::VectorXd& q_tilde, const Configuration& c_n, StepStats& stats,
                             std::vector<EnergyTerm*>& terms, std::vector<int>& held);
  /// Newton's starting point: every dynamic body moved rigidly (p from q̃, A turned by
  /// exp([ω]× h)), kinematic bodies onto their target (q̃), as far along the straight line from
  /// qⁿ as CCD allows; bodies in contact at qⁿ start without q̃'s free fall β h² g (they rest
  /// on something). Starting at qⁿ would make Newton turn a spinning body through linearised
  /// rotations, each of which stretches it against the stiff orthogonality potential.
  Eigen::VectorXd initial_guess(const Eigen::VectorXd& q_tilde, const Configuration& c_n) const;
  /// Minimises the step's energy from q with the prescribed DOF blocks held on their path q̃:
  /// directly when they can be put there without intersection (from the initial guess, or
  /// from qⁿ moving them alone); otherwise pulled toward it by the inertia weight, raised
  /// tenfold per round, until the rest of the path is free, then held. With joints' eliminated
  /// equalities they are only pulled, to within the step-size tolerance. PhysicsError when
  /// no round gets there.
  NewtonReport follow_paths(const std::vector<EnergyTerm*>& terms, const Eigen::VectorXd& q_tilde,
                            const NewtonSettings& ns, Eigen::VectorXd& q);
  /// q with the prescribed DOF blocks taken from q̃.
  Eigen::VectorXd on_path(const Eigen::VectorXd& q, const Eigen::VectorXd& q_tilde) const;
  /// Whether the straight move from `from` to `to` is free of intersection (CCD, joint limits).
  bool moves_freely(const Eigen::VectorXd& from, const Eigen::VectorXd& to) const;
  /// How far the prescribed DOFs of q are from their path (largest surface-point or node
  /// distance, m), and the body of the farthest.
  std::pair<double, int> path_lag(const Eigen::VectorXd& q, const Eigen::VectorXd& q_tilde) const;
  /// The PhysicsError of a prescribed motion that cannot be followed.
  PhysicsError path_blocked(const Eigen::VectorXd& q, const Eigen::VectorXd& q_tilde) const;
  /// Throws PhysicsError when an affine body of q exceeds the rigidity bound.
  void check_rigidity(const Eigen::VectorXd& q) const;
  /// The step when every dynamic body sleeps: nothing moves, no Newton iteration.
  StepStats sleeping_step();
  /// The DOFs of `blocks` in v set to those of `from`.
  void copy_blocks(const std::vector<int>& blocks, const Eigen::VectorXd& from, Eigen::VectorXd& v) const;
  /// Fills what stats reports of the state at the end of a step (contacts, energies, momentum,
  /// rigidity, soft elements, joints' error, sleep) and its wall time; x: the surface at q.
  void finish_stats(StepStats& stats, const Eigen::MatrixX3d& x, std::chrono::steady_clock::time_point start);
  /// Fills m_joint_forces at the end of a step: `terms` are the step's energy terms, already
  /// updated at q.
  void compute_joint_forces(const std::vector<EnergyTerm*>& terms, const Configuration& c);

  Model m_model;
  SimulationSettings m_settings;
  std::unique_ptr<LinearSolver> m_solver;
  BlockHessian m_hessian;  ///< Newton's Hessian, its storage kept from step to step
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
  std::function<void(const NewtonIterate&)> m_newton_observer;
  std::vector<int> m_prescribed_blocks;  // DOF blocks of kinematic bodies and prescribed soft nodes
  std::optional<Sleeping> m_sleeping;     // with sleep_time > 0
  bool m_slept = false;                   // whether the last step was a sleeping_step()
  Eigen::VectorXd m_q, m_qdot, m_q_prev, m_qdot_prev, m_gravity_q;
  double m_time = 0;
  int m_step = 0;
};

}  // namespace stiffsoft
