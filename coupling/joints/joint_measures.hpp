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
  HingeAngle   ///< atan2(n·(e_b × e_a), e_a·e_b) (rad): rotation of e_a from e_b about the (unit) axis n; y = [e_a; e_b; n]
};

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
/// singular (not reached: joints start with non-degenerate geometry).
MeasureValue measure_derivatives(JointMeasure measure, const Eigen::VectorXd& y);

}  // namespace stiffsoft
