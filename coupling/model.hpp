#pragma once
/// @file The immutable model of a scene of affine bodies: bodies, their mass, and the one
/// collision mesh that maps configurations to surface points (x = A x̄ + p per body).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "libabd/affine_body.hpp"

namespace stiffsoft {

/// How a body's configuration evolves.
enum class Motion {
  Dynamic,   ///< free affine body: 12 DOFs, inertia, orthogonality, gravity, contact
  Fixed,     ///< static obstacle: no DOFs
  Kinematic  ///< prescribed rigid motion, followed through a stiff pull (12 DOFs, see docs/architecture.md)
};

/// One body of the model.
struct BodyModel {
  std::string name;                        ///< unique name (ParaView block name)
  Motion motion = Motion::Dynamic;
  int dof = -1;                            ///< offset of its 12 DOFs in q; −1 when Fixed
  abd::Matrix12d M = abd::Matrix12d::Zero();  ///< mass matrix ∫ρJᵀJ (kg, kg·m, kg·m²)
  double mass = 0;                         ///< kg
  double volume = 0;                       ///< ν (m³)
  double kappa = 0;                        ///< orthogonality stiffness κ (Pa)
  abd::Vector12d q0 = abd::Vector12d::Zero();  ///< initial configuration
  Eigen::Vector3d v0 = Eigen::Vector3d::Zero();  ///< initial (Kinematic: prescribed) linear velocity (m/s)
  Eigen::Vector3d w0 = Eigen::Vector3d::Zero();  ///< initial (Kinematic: prescribed) angular velocity, world (rad/s)
  int vertex_begin = 0, vertex_end = 0;    ///< its surface vertices in the collision mesh
  int face_begin = 0, face_end = 0;        ///< its triangles
  int edge_begin = 0, edge_end = 0;        ///< its edges
};

/// The surfaces of all bodies, concatenated.
struct CollisionMesh {
  Eigen::MatrixX3d x_bar;        ///< body-frame positions, |V|×3, m (centred at each body's centre of mass)
  std::vector<int> vertex_body;  ///< body of each vertex, |V|
  Eigen::MatrixX3i F;            ///< triangles, global vertex indices, |F|×3
  Eigen::MatrixX2i E;            ///< edges, global vertex indices, |E|×2
  std::vector<int> face_body;    ///< body of each triangle
  std::vector<int> edge_body;    ///< body of each edge
};

/// Bodies plus collision mesh: everything that does not change during a run.
struct Model {
  std::vector<BodyModel> bodies;
  CollisionMesh mesh;
  int num_dofs = 0;  ///< 12 × (number of non-fixed bodies)

  /// Body b's configuration: from q for bodies with DOFs, q0 for fixed ones.
  abd::Vector12d body_q(int b, const Eigen::VectorXd& q) const {
    const BodyModel& body = bodies[b];
    return body.dof < 0 ? body.q0 : abd::Vector12d(q.segment<12>(body.dof));
  }
  /// Surface positions x(q), |V|×3 (m).
  Eigen::MatrixX3d surface(const Eigen::VectorXd& q) const;
  /// Surface displacement Φ dq of a DOF step dq, |V|×3 (m): fixed bodies do not move.
  Eigen::MatrixX3d surface_step(const Eigen::VectorXd& dq) const;
  /// The DOF vector of the initial configuration.
  Eigen::VectorXd initial_q() const;
  /// The DOF velocity of the initial (rigid) velocities.
  Eigen::VectorXd initial_qdot() const;
  /// Length of the diagonal of the axis-aligned box around the initial surfaces (m).
  double bounding_box_diagonal() const;
};

}  // namespace stiffsoft
