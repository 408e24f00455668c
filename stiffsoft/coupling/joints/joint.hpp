#pragma once
/// @file Joints of the model (Chen, Li et al. 2022, "A Unified Newton Barrier Method for
/// Multibody Dynamics", §4): what a joint connects and which constraint it imposes. How each
/// constraint is enforced is decided by its kind: linear equalities are eliminated by a change
/// of variables (linear_constraints.hpp, reduced_basis.hpp), nonlinear equalities are stiff
/// penalties and inequalities barrier potentials (terms/joint_term.hpp). See docs/joints.md.

#include <array>
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace stiffsoft {

/// What a joint constrains.
enum class JointKind {
  Ball,            ///< point connection: a point of body a coincides with a point of body b (or the world); linear, 3 rows
  Hinge,           ///< two points on a common axis coincide: rotation about the axis only; linear, 6 rows (+ optional rotation range)
  Prismatic,       ///< relative orientation locked (linear, 9 rows) + a point of b stays on an axis of a (penalty) (+ optional sliding range)
  Distance,        ///< |x_a − x_b| stays at its initial length (stiff penalty)
  BoundedDistance, ///< lower ≤ |x_a − x_b| ≤ upper (barrier potentials, never violated)
  ConeTwist        ///< a ball joint (linear, 3 rows) whose axis carried by both bodies may bend up to `swing` and twist within [lower, upper] (barriers)
};

/// The name of each kind as written in scene files, indexed by JointKind.
inline constexpr std::array<const char*, 6> kJointKindNames{"ball",     "hinge",            "prismatic",
                                                            "distance", "bounded_distance", "cone_twist"};

/// Number of joint kinds (JointKind(0) … JointKind(kJointKindCount − 1)).
constexpr int kJointKindCount = int(kJointKindNames.size());

/// The name of a kind as written in scene files ("ball", "hinge", ...).
inline const char* joint_kind_name(JointKind kind) { return kJointKindNames.at(std::size_t(kind)); }

/// One end of a joint: a point (and frame vectors) carried by an affine body, a soft node, or
/// the world (fixed bodies count as the world: their points never move).
struct JointEnd {
  int body = -1;  ///< body index in Model::bodies; −1: the world
  int node = -1;  ///< soft node (Model::nodes) when the end is on a soft body; −1 otherwise
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  ///< affine: body-frame x̄ (m, centred at the centre of mass); world: world point (m); node: unused
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();    ///< hinge/prismatic/cone-twist: unit axis, body frame (world for the world)
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();  ///< hinge/cone-twist: unit vector ⟂ axis that measures the rotation (twist) angle, body frame
};

/// A further soft node pinned to body a by a ball joint (scene key `nodes_within`): 3 more
/// linear rows, node = A_a x̄ + p_a.
struct NodePin {
  int node = -1;                                     ///< soft node (Model::nodes)
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  ///< body a's material point x̄ at the node's initial position (body frame, m)
};

/// One joint between body a (affine, dynamic or kinematic) and body b (affine, the world, or a
/// soft node for ball joints). Built from the scene at the initial pose, so the initial
/// configuration satisfies every equality by construction.
struct JointModel {
  std::string name;                 ///< unique name, for errors and output
  JointKind kind = JointKind::Ball;  ///< constraint kind
  JointEnd a;                       ///< first end (an affine body)
  JointEnd b;                       ///< second end (affine body, world, or soft node)
  double axis_length = 1;           ///< hinge: distance between the two connected axis points (m)
  double rest_length = 0;           ///< distance: the length kept (m)
  double stiffness = 0;             ///< penalty stiffness k (N/m) of distance and prismatic joints
  std::optional<double> lower;      ///< hinge: lowest angle (rad); prismatic: lowest slide (m); bounded distance: shortest length (m); cone-twist: lowest twist (rad)
  std::optional<double> upper;      ///< hinge: highest angle (rad); prismatic: highest slide (m); bounded distance: longest length (m); cone-twist: highest twist (rad)
  std::optional<double> swing;      ///< cone-twist: largest bend of body a's axis from body b's (rad, in (0, π))
  std::vector<NodePin> pins;        ///< ball joint to a soft body: further nodes pinned to body a, besides b.node
  double limit_stiffness = 1;       ///< barrier stiffness κ of the limits (J): energy κ b(gap/ĝ), b(x) = −(x − 1)² ln x
  double limit_activation = 0.05;   ///< barrier activation gap ĝ of the limits (rad or m)
  double damping = 0;               ///< viscous damping c of the joint's free coordinate (N·m·s/rad or N·s/m); ball and cone-twist: of the relative angular velocity (N·m·s/rad)
};

}  // namespace stiffsoft
