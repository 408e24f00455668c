#pragma once
/// @file The immutable model of a scene: affine bodies (12 DOFs each, x = A x̄ + p), soft
/// bodies (tetrahedral FEM, 3 DOFs per free node), and the one collision mesh that maps the
/// DOF vector q to surface points. Newton sees q as a list of DOF blocks (12 or 3 wide) and
/// never asks which kind of body a block belongs to.

#include <Eigen/Core>
#include <string>
#include <vector>

#include <stiffsoft/coupling/joints/joint.hpp>
#include <stiffsoft/libabd/affine_body.hpp>

namespace stiffsoft {

/// How a body (or a soft node) moves.
enum class Motion {
  Dynamic,   ///< free: inertia, elasticity or orthogonality, gravity, contact
  Fixed,     ///< static: no DOFs
  Kinematic  ///< prescribed motion, followed through a stiff pull (DOFs, see docs/architecture.md)
};

/// How a body is discretised.
enum class Representation {
  Affine,  ///< one affine element: 12 DOFs (Lan et al. 2022)
  Soft     ///< linear tetrahedra: 3 DOFs per node that is not fixed
};

/// Material of a soft body (libfem's constitutive models).
struct SoftMaterial {
  std::string model = "stable_neo_hookean";  ///< "linear", "fixed_corotated", "stable_neo_hookean"
  double young = 1e6;                         ///< Young's modulus E (Pa)
  double poisson = 0.4;                       ///< Poisson ratio ν, in (−1, 0.5)
};

/// One leg of a kinematic body's prescribed path: constant velocities for a duration.
struct PathSegment {
  double duration = 0;                              ///< s, > 0
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< linear velocity of the centre of mass (m/s)
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< world frame (rad/s)
};

/// A contiguous group of DOFs that Newton's block-sparse Hessian treats as one block.
struct DofBlock {
  int offset = 0;  ///< first DOF in q
  int size = 0;    ///< 12 (affine body) or 3 (soft node)
};

/// One body of the model.
struct BodyModel {
  std::string name;                        ///< unique name (ParaView block name)
  Representation representation = Representation::Affine;
  Motion motion = Motion::Dynamic;         ///< affine: the body's motion; soft: Dynamic (its nodes may be fixed or kinematic)
  int dof = -1;                            ///< affine: offset of its 12 DOFs in q; −1 when Fixed or soft
  int block = -1;                          ///< affine: its DOF block; −1 when Fixed or soft
  abd::Matrix12d M = abd::Matrix12d::Zero();  ///< affine: mass matrix ∫ρJᵀJ (kg, kg·m, kg·m²)
  double mass = 0;                         ///< kg
  double volume = 0;                       ///< ν (m³)
  double kappa = 0;                        ///< affine: orthogonality stiffness κ (Pa)
  abd::Vector12d q0 = abd::Vector12d::Zero();  ///< affine: initial configuration
  Eigen::Vector3d v0 = Eigen::Vector3d::Zero();  ///< initial (Kinematic: prescribed) linear velocity (m/s)
  Eigen::Vector3d w0 = Eigen::Vector3d::Zero();  ///< initial (Kinematic: prescribed) angular velocity, world (rad/s)
  std::vector<PathSegment> path;           ///< Kinematic: legs followed first, then v_after, w_after for ever
  Eigen::Vector3d v_after = Eigen::Vector3d::Zero();  ///< Kinematic: linear velocity after the path (m/s)
  Eigen::Vector3d w_after = Eigen::Vector3d::Zero();  ///< Kinematic: angular velocity after the path (rad/s)
  SoftMaterial material;                   ///< soft: constitutive model
  double density = 0;                      ///< ρ (kg/m³)
  int node_begin = 0, node_end = 0;        ///< soft: its nodes in Model::nodes
  int tet_begin = 0, tet_end = 0;          ///< soft: its tetrahedra in Model::nodes.T
  int vertex_begin = 0, vertex_end = 0;    ///< its surface vertices in the collision mesh
  int face_begin = 0, face_end = 0;        ///< its triangles
  int edge_begin = 0, edge_end = 0;        ///< its edges
  /// True when the body's own surface can touch itself (soft bodies self-collide).
  bool self_contact() const { return representation == Representation::Soft; }
  /// True when the body carries DOFs (a dynamic or kinematic affine body, a soft body): it may move.
  bool carries_dofs() const { return dof >= 0 || representation == Representation::Soft; }
};

/// The nodes and tetrahedra of all soft bodies, concatenated.
struct SoftNodes {
  Eigen::MatrixX3d X;              ///< rest (and initial) positions, world frame, |N|×3 (m)
  Eigen::MatrixX4i T;              ///< tetrahedra, global node indices, positively oriented
  Eigen::VectorXd mass;            ///< lumped mass per node (kg)
  std::vector<Motion> motion;      ///< Dynamic, Fixed (Dirichlet), or Kinematic (prescribed velocity)
  Eigen::MatrixX3d velocity;       ///< initial (Kinematic: prescribed) velocity per node (m/s)
  std::vector<int> dof;            ///< offset of the node's 3 DOFs in q; −1 when Fixed
  std::vector<int> block;          ///< the node's DOF block; −1 when Fixed
  std::vector<int> body;           ///< body of each node
  /// Number of nodes.
  int size() const { return int(X.rows()); }
};

/// The surfaces of all bodies, concatenated.
struct CollisionMesh {
  Eigen::MatrixX3d x_bar;        ///< affine: body-frame positions (centred at the centre of mass); soft: rest positions; |V|×3, m
  std::vector<int> vertex_body;  ///< body of each vertex, |V|
  std::vector<int> vertex_node;  ///< soft node of each vertex, −1 for affine vertices, |V|
  Eigen::MatrixX3i F;            ///< triangles, global vertex indices, |F|×3
  Eigen::MatrixX2i E;            ///< edges, global vertex indices, |E|×2
  std::vector<int> face_body;    ///< body of each triangle
  std::vector<int> face_tet;     ///< soft: tetrahedron (row of Model::nodes.T) of each boundary triangle; −1 for affine
  std::vector<int> edge_body;    ///< body of each edge
};

/// Bodies, soft nodes, DOF blocks and collision mesh: everything that does not change during a run.
struct Model {
  std::vector<BodyModel> bodies;   ///< every body, affine and soft
  SoftNodes nodes;                 ///< soft bodies' nodes and tets
  CollisionMesh mesh;              ///< every body's surface
  std::vector<DofBlock> blocks;    ///< the DOF blocks of q, in order
  std::vector<JointModel> joints;  ///< joints between bodies (coupling/joints/, docs/joints.md)
  int num_dofs = 0;                ///< size of q

  /// Appends a DOF block of `size` DOFs and returns its index.
  int add_block(int size);
  /// Body b's affine configuration: from q for affine bodies with DOFs, q0 for fixed ones.
  abd::Vector12d body_q(int b, const Eigen::VectorXd& q) const {
    const BodyModel& body = bodies[b];
    return body.dof < 0 ? body.q0 : abd::Vector12d(q.segment<12>(body.dof));
  }
  /// The prescribed configuration of kinematic body b at time t (s): its path's legs in
  /// order, then (v_after, w_after).
  abd::Vector12d kinematic_q(int b, double t) const;
  /// Positions of all soft nodes, |N|×3 (m): from q, or the rest position for fixed nodes.
  Eigen::MatrixX3d node_positions(const Eigen::VectorXd& q) const;
  /// Surface positions x(q), |V|×3 (m).
  Eigen::MatrixX3d surface(const Eigen::VectorXd& q) const;
  /// Surface displacement Φ dq of a DOF step dq, |V|×3 (m): fixed bodies and nodes do not move.
  Eigen::MatrixX3d surface_step(const Eigen::VectorXd& dq) const;
  /// The DOF vector of the initial configuration.
  Eigen::VectorXd initial_q() const;
  /// The DOF velocity of the initial velocities.
  Eigen::VectorXd initial_qdot() const;
  /// Length of the diagonal of the axis-aligned box around the initial surfaces (m).
  double bounding_box_diagonal() const;
  /// True when some body is soft.
  bool has_soft_bodies() const { return nodes.size() > 0; }
};

}  // namespace stiffsoft
