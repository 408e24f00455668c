#pragma once
/// @file The scalar quantities nonlinear joints are written in, as functions of stacked world
/// vectors y (joint_vectors.hpp), with gradient and Hessian in y. Penalties and barriers of
/// terms/joint_term.hpp wrap them.

#include <Eigen/Core>

namespace stiffsoft {

/// Which scalar a joint potential measures.
enum class JointMeasure {
  Distance,    ///< |x_a − x_b| (m); y = [x_a; x_b]
  Slide,       ///< (x_a − x_b)·u/|u| (m): the slide of a along b's axis u; y = [x_a; x_b; u]
  OffAxis,     ///< |r|² − (r·u)²/|u|², r = x_a − x_b (m²): squared distance of x_a from b's axis line; y = [x_a; x_b; u]
  HingeAngle,  ///< atan2(n·(e_b × e_a), e_a·e_b) (rad): rotation of e_a from e_b about the (unit) axis n; y = [e_a; e_b; n]
  BendAngle,   ///< atan2(|e_a × e_b|, e_a·e_b) ∈ [0, π] (rad): the angle between two axes; y = [e_a; e_b]
  TwistAngle   ///< rotation of r_a from r_b about the axis once the bend is undone (rad, see twist_angle()); y = [e_a; e_b; r_a; r_b]
};

/// True for the measures that are angles (their gradient is a torque, not a force).
bool measure_is_angle(JointMeasure measure);

/// A measure s(y) with ∇s and ∇²s.
struct MeasureValue {
  double s = 0;           ///< s(y)
  Eigen::VectorXd grad;   ///< ∇_y s
  Eigen::MatrixXd hess;   ///< ∇²_y s (symmetric)
};

/// Number of stacked vectors the measure takes (y has 3× as many entries).
int measure_vectors(JointMeasure measure);

/// s(y) only.
double measure(JointMeasure measure, const Eigen::VectorXd& y);

/// s(y), its gradient and Hessian. Distance at |r| = 0 and Slide/OffAxis at u = 0 are
/// singular (not reached: joints start with non-degenerate geometry). BendAngle is singular at
/// bend 0 and π (a cone's tip: |e_a × e_b| is not differentiable there) and TwistAngle at bend
/// π; a barrier on them is only differentiated where it is active, away from 0 (JointTerm).
MeasureValue measure_derivatives(JointMeasure measure, const Eigen::VectorXd& y);

/// The twist of a cone-twist joint (swing-twist decomposition): S is the smallest rotation
/// that takes ê_a = e_a/|e_a| onto ê_b (about ê_a × ê_b, by the bend angle),
/// S v = c v + w × v + (w·v) w / (1 + c) with w = ê_a × ê_b, c = ê_a·ê_b; the twist is the
/// angle of S r_a from r_b about ê_b, atan2(ê_b·(r_b × S r_a), r_b·S r_a) (rad). It is 0 at
/// the initial pose (e_a = e_b, r_a = r_b ⟂ e), exactly the rotation about the axis for a pure
/// twist, 0 for a pure bend (S removes it), and smooth everywhere except at bend π (c = −1),
/// where the smallest rotation is not unique. r_a and r_b are the bodies' reference vectors
/// ⟂ axis; y = [e_a; e_b; r_a; r_b].
double twist_angle(const Eigen::Vector3d& e_a, const Eigen::Vector3d& e_b, const Eigen::Vector3d& r_a,
                   const Eigen::Vector3d& r_b);

/// ∂ω/∂ẏ at y: the relative angular velocity ω = ω_a − ω_b (rad/s, world frame) of two frames
/// as a linear function of the rates of their columns, y = [f_a1; f_a2; f_a3; f_b1; f_b2; f_b3]
/// (f_k = A e_k, the world images of a body's frame axes): ω_a = ½ Σ_k f_k × ḟ_k, exact for an
/// orthonormal frame (ḟ_k = ω × f_k gives ½ Σ_k f_k × (ω × f_k) = ½ (3ω − ω) = ω). Used by the
/// lagged damping of ball and cone-twist joints, evaluated at the step's start.
Eigen::Matrix<double, 3, 18> relative_angular_velocity_jacobian(const Eigen::VectorXd& y);

}  // namespace stiffsoft
