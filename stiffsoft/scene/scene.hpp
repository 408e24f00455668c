#pragma once
/// @file The scene as read from JSON: plain settings structs, filled with every default.
/// The scene loader (stiffsoft/scene/scene_loader.hpp) is the only place that turns JSON into these.
/// The defaults written here are the scene schema's defaults too (scene_schema.cpp copies them
/// from default-constructed structs), so a default is changed here and only here.

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <stiffsoft/coupling/solver/integrator.hpp>
#include <stiffsoft/coupling/solver/newton.hpp>
#include <stiffsoft/coupling/solver/simulation_settings.hpp>
#include <stiffsoft/coupling/linear_solver/forcing_term.hpp>
#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/meshing/primitive.hpp>

namespace stiffsoft {


/// `time`: step size, duration, integrator.
struct TimeDescription {
  double dt = SimulationSettings{}.h;  ///< time step h (s), > 0
  double duration = 1.0;   ///< simulated time (s), > 0
  Integrator integrator = Integrator::BackwardEuler;
};

/// `contact.pairs[]`: settings for the contacts between two named bodies.
struct ContactPairDescription {
  std::string body_a;  ///< name of a body
  std::string body_b;  ///< name of a body (may equal body_a: a soft body's self-contact)
  double damping = 0;  ///< lagged Rayleigh damping k_d of this pair's contacts (s), ≥ 0; replaces contact.damping
};

/// `contact`: the IPC barrier and friction. Lengths in metres, speeds in m/s; an unset value
/// is relative to the scene's bounding-box diagonal (see docs/units.md).
struct ContactDescription {
  std::optional<double> dhat;   ///< barrier activation distance d̂ (m); default 1e-3 × diagonal, at most 1 % of the smallest body
  double mu = SimulationSettings{}.mu;  ///< Coulomb friction coefficient, ≥ 0; 0 turns friction off
  std::optional<double> eps_v;  ///< static/kinetic smoothing speed ε_v (m/s); default 1e-3 × diagonal / s
  std::optional<double> kappa;  ///< barrier stiffness (Pa·m, fixed); default adaptive (IPC's rule)
  bool balance_kappa = SimulationSettings{}.balance_kappa;  ///< adaptive κ balanced once, at the first contact
  int friction_iterations = SimulationSettings{}.friction_iterations;  ///< friction lags per step, ≥ 1
  double damping = SimulationSettings{}.contact_damping;  ///< lagged Rayleigh damping k_d of contacts (s), ≥ 0; 0: none
  bool check_start_gaps = true;  ///< refuse bodies starting closer than d̂, and d̂ above 1 % of a body's size (start_gaps.hpp)
  std::vector<ContactPairDescription> pairs;  ///< per body pair settings, overriding the above for that pair
};

/// `solver`: Newton's stopping rule and the linear solver.
struct SolverDescription {
  std::optional<double> tolerance;  ///< ε_d (m/s): stop when max surface-point step / h < ε_d; default 1e-2 × diagonal / s
  double gap_tolerance = NewtonSettings{}.gap_tolerance;  ///< Newton's largest relative change of a contact gap at convergence, > 0
  int max_iterations = NewtonSettings{}.max_iterations;  ///< Newton iteration cap per solve, ≥ 1
  contact::BarrierHessian barrier_hessian = SimulationSettings{}.barrier_hessian;  ///< Newton's Hessian of the barrier stencils
  double release_hessian = SimulationSettings{}.release_hessian;  ///< fraction of its Hessian a contact Newton releases keeps, in (0, 1]
  bool geodesic_line_search = SimulationSettings{}.geodesic_line_search;  ///< line-search trials turn affine bodies along the rotation group
  bool island_line_search = SimulationSettings{}.island_line_search;  ///< each island of uncoupled bodies its own CCD bound and step
  bool entering_springs = SimulationSettings{}.entering_springs;  ///< a direction CCD cuts is solved again with springs on the pairs entering d̂
  std::string linear = SimulationSettings{}.linear_solver;  ///< linear solver backend (see make_linear_solver())
  double krylov_rtol_max = ForcingTermSettings{}.eta_max;  ///< η_max: largest relative residual a Krylov solve may stop at
  double rigidity_bound = SimulationSettings{}.rigidity_bound;  ///< largest ‖AᵀA − I‖_F an affine body may reach before the run stops
  double sleep_time = SimulationSettings{}.sleep_time;  ///< t_s (s): affine bodies at rest this long sleep; 0: never
  std::optional<double> sleep_speed;  ///< v_s (m/s): the speed below which a body rests; default the tolerance ε_d
};

/// `output`: what is written and how often.
struct OutputDescription {
  std::optional<double> frame_dt;  ///< time between written frames (s); default max(dt, 1/60)
};

/// How a dynamic body is discretised.
enum class ModelChoice {
  Affine,  ///< one affine element, 12 DOFs
  Soft,    ///< tetrahedral FEM
  Auto     ///< affine when stiff enough for the scene's loads, soft otherwise (scene_builder.hpp)
};

/// One entry of `dirichlet`: which nodes of a soft body are prescribed, and how they move.
struct DirichletDescription {
  /// How the nodes are selected.
  enum class Select {
    Box,        ///< inside [min, max]
    HalfSpace,  ///< (x − point)·normal ≥ 0
    NodeSet     ///< a named node set of the mesh file
  };
  Select select = Select::Box;                          ///< selection rule
  Eigen::Vector3d min = Eigen::Vector3d::Zero();        ///< box lower corner (m)
  Eigen::Vector3d max = Eigen::Vector3d::Zero();        ///< box upper corner (m)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();      ///< half-space plane point (m)
  Eigen::Vector3d normal{0.0, -1.0, 0.0};              ///< half-space direction (need not be unit); not −UnitY(), whose −0 entries docs/scenes.md would show
  std::string node_set;                                 ///< node-set name
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();   ///< prescribed velocity (m/s); zero: fixed
};

/// Where a body's surface comes from: a file or a primitive.
struct MeshDescription {
  std::filesystem::path file;              ///< .obj, .stl, .msh, .step, .stp, .brep or .geo (absolute, resolved against the scene's folder); empty for a primitive
  std::optional<PrimitiveShape> primitive; ///< set when the mesh is a primitive
};

/// One entry of `bodies`.
struct BodyDescription {
  std::string name;                      ///< unique, used as the ParaView block name
  Motion kind = Motion::Dynamic;         ///< how it moves: dynamic (affine or soft, see `model`), fixed, or kinematic
  ModelChoice model = ModelChoice::Affine;  ///< how a dynamic body is discretised
  MeshDescription mesh;                  ///< its geometry
  double density = 1000.0;               ///< kg/m³, > 0
  SoftMaterial material;                 ///< `material` of soft and auto bodies
  std::optional<double> mesh_size;       ///< target tet edge length (m); unset: 1/8 of the body's box diagonal
  std::vector<DirichletDescription> dirichlet;  ///< prescribed nodes of a soft body
  double kappa = 1e8;                    ///< orthogonality stiffness κ (Pa), > 0
  Eigen::Vector3d position = Eigen::Vector3d::Zero();        ///< where the mesh's origin goes (m)
  Eigen::Vector3d rotation_deg = Eigen::Vector3d::Zero();    ///< XYZ Euler angles (degrees), R = Rz Ry Rx
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();           ///< per-axis scale applied before rotation
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();        ///< initial (or prescribed) linear velocity of the centre of mass (m/s)
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();///< initial (or prescribed) angular velocity, world frame (rad/s)
  std::vector<PathSegment> path;         ///< kinematic: legs of constant velocity followed before velocity/angular_velocity
};

/// One entry of `joints` (docs/joints.md). Points and axes are given in the world frame at the
/// initial pose.
struct JointDescription {
  std::string name;                                   ///< unique, for errors and output
  JointKind kind = JointKind::Ball;                   ///< what it constrains
  std::string body_a;                                 ///< an affine body (dynamic or kinematic)
  std::string body_b = "world";                       ///< another body, or "world"
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();   ///< the joint point, on body a (m)
  std::optional<Eigen::Vector3d> anchor_b;            ///< distance kinds: the point on body b (m)
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();    ///< hinge, prismatic and cone-twist axis (need not be unit)
  double stiffness = 1e6;                             ///< penalty stiffness of distance and prismatic joints (N/m)
  std::optional<double> lower;                        ///< lower limit (rad for hinges, m otherwise); unset: none
  std::optional<double> upper;                        ///< upper limit (rad for hinges, m otherwise); unset: none
  std::optional<double> swing;                        ///< cone-twist: largest bend (rad); unset: none
  std::optional<double> twist_lower;                  ///< cone-twist: lowest twist (rad, < 0); unset: none
  std::optional<double> twist_upper;                  ///< cone-twist: highest twist (rad, > 0); unset: none
  std::optional<double> limit_stiffness;              ///< limit barrier stiffness κ (J); unset: automatic (scene_builder.hpp)
  double limit_activation = 0.05;                     ///< limit barrier activation gap ĝ (rad or m)
  double damping = 0.0;                               ///< viscous damping of the free coordinate (N·m·s/rad or N·s/m; ball, cone-twist: relative angular velocity)
  std::optional<double> nodes_within;                 ///< ball joint to a soft body: pin every node within this distance of anchor (m); unset: the nearest node only
};

/// A whole scene, every default filled in.
struct SceneDescription {
  std::string name;         ///< from the file name (stem)
  std::string description;  ///< what the scene shows and how to run it
  TimeDescription time;
  Eigen::Vector3d gravity = SimulationSettings{}.gravity;  ///< m/s²
  ContactDescription contact;
  SolverDescription solver;
  OutputDescription output;
  std::vector<BodyDescription> bodies;
  std::vector<JointDescription> joints;  ///< joints between bodies (may be empty)
};

}  // namespace stiffsoft
