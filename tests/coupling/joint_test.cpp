/// @file Joints' building blocks: the measures' and potentials' derivatives against finite
/// differences, the elimination of linear equalities (chains, loops, redundant and
/// inconsistent rows), the limit barriers' step bound, and the damping term.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include <stiffsoft/coupling/joints/joint_measures.hpp>
#include <stiffsoft/coupling/joints/linear_constraints.hpp>
#include <stiffsoft/coupling/joints/reduced_basis.hpp>
#include <stiffsoft/coupling/terms/damping_term.hpp>
#include <stiffsoft/coupling/terms/joint_term.hpp>
#include "finite_differences.hpp"
#include <stiffsoft/libabd/affine_body.hpp>

using namespace stiffsoft;
using namespace stiffsoft::testing;

namespace {

/// A model of `count` dynamic affine bodies (no surfaces), body i at (i, 0, 0) turned by a
/// fixed rotation, plus `fixed` fixed bodies after them.
Model bodies_model(int count, int fixed = 0) {
  Model model;
  for (int i = 0; i < count + fixed; ++i) {
    BodyModel body;
    body.name = "body" + std::to_string(i);
    body.motion = i < count ? Motion::Dynamic : Motion::Fixed;
    if (i < count) {
      body.block = model.add_block(12);
      body.dof = model.blocks[body.block].offset;
    }
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3 + 0.2 * i, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    body.q0 = abd::make_q(Eigen::Vector3d(i, 0.1 * i, 0), R);
    model.bodies.push_back(body);
  }
  return model;
}

/// An end on body b at world point x (axis, reference in the world) for the model's initial pose.
JointEnd end_at(const Model& model, int b, const Eigen::Vector3d& x, const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ()) {
  JointEnd end;
  end.body = b;
  const Eigen::Vector3d reference = axis.cross(Eigen::Vector3d::UnitX()).normalized();
  if (b < 0) {
    end.anchor = x;
    end.axis = axis;
    end.reference = reference;
    return end;
  }
  const Eigen::Matrix3d A_inv = abd::affine_matrix(model.bodies[b].q0).inverse();
  end.anchor = A_inv * (x - abd::translation(model.bodies[b].q0));
  end.axis = A_inv * axis;
  end.reference = A_inv * reference;
  return end;
}

JointModel joint(const Model& model, JointKind kind, int a, int b, const Eigen::Vector3d& x,
                 const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ()) {
  JointModel j;
  j.name = std::string(joint_kind_name(kind)) + std::to_string(a) + "_" + std::to_string(b);
  j.kind = kind;
  j.a = end_at(model, a, x, axis);
  j.b = end_at(model, b, x, axis);
  j.axis_length = 0.5;
  return j;
}

/// q0 plus a small random perturbation (so bodies are slightly non-rigid and moved).
Eigen::VectorXd perturbed(const Model& model, double size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-size, size);
  Eigen::VectorXd q = model.initial_q();
  for (Eigen::Index i = 0; i < q.size(); ++i) q[i] += u(rng);
  return q;
}

}  // namespace

TEST(JointMeasures, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (JointMeasure m : {JointMeasure::Distance, JointMeasure::Slide, JointMeasure::OffAxis, JointMeasure::HingeAngle,
                         JointMeasure::BendAngle, JointMeasure::TwistAngle}) {
    for (int trial = 0; trial < 5; ++trial) {
      Eigen::VectorXd y(3 * measure_vectors(m));
      for (Eigen::Index i = 0; i < y.size(); ++i) y[i] = u(rng);
      const MeasureValue v = measure_derivatives(m, y);
      EXPECT_NEAR(v.s, measure(m, y), 1e-13) << "measure " << int(m);
      const Eigen::VectorXd g = fd_gradient([&](const Eigen::VectorXd& x) { return measure(m, x); }, y);
      const Eigen::MatrixXd H = fd_jacobian([&](const Eigen::VectorXd& x) { return measure_derivatives(m, x).grad; }, y);
      EXPECT_LT(relative_error(v.grad, g), 1e-6) << "measure " << int(m);
      EXPECT_LT(relative_error(v.hess, H), 1e-5) << "measure " << int(m);
      EXPECT_LT((v.hess - v.hess.transpose()).norm(), 1e-12 * std::max(1.0, v.hess.norm()));
    }
  }
}

TEST(JointMeasures, HingeAngleIsTheRotationAboutTheAxis) {
  const Eigen::Vector3d n(0, 0, 1), e_b(1, 0, 0);
  for (double theta : {-2.5, -0.3, 0.0, 0.7, 3.0}) {
    Eigen::VectorXd y(9);
    y << std::cos(theta), std::sin(theta), 0, e_b, n;
    EXPECT_NEAR(measure(JointMeasure::HingeAngle, y), theta, 1e-14);
  }
}

TEST(JointMeasures, BendAndTwistAreTheSwingAndTwistOfTheRelativeRotation) {
  // Body b in any orientation Q; body a turned relative to it by a twist τ about the axis e
  // followed by a swing β about an axis ⟂ e: bend = β, twist = τ, whatever Q and the swing's
  // direction. At β → π the twist is undefined, so β stays below.
  const Eigen::Vector3d e = Eigen::Vector3d(0.2, 1, -0.3).normalized();
  const Eigen::Vector3d r = e.cross(Eigen::Vector3d::UnitX()).normalized();
  for (const double beta : {0.0, 0.4, 1.3, 2.8})
    for (const double tau : {-2.5, -0.6, 0.0, 0.3, 1.7})
      for (const double phi : {0.0, 1.1, 4.0}) {  // direction of the swing axis about e
        const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
        const Eigen::Vector3d swing_axis = Eigen::AngleAxisd(phi, e) * r;
        const Eigen::Matrix3d R = (Eigen::AngleAxisd(beta, swing_axis) * Eigen::AngleAxisd(tau, e)).toRotationMatrix();
        Eigen::VectorXd y(12);
        y << Q * R * e, Q * e, Q * R * r, Q * r;
        EXPECT_NEAR(measure(JointMeasure::BendAngle, y.head<6>()), beta, 1e-12);
        EXPECT_NEAR(measure(JointMeasure::TwistAngle, y), tau, 1e-12) << "β " << beta << " φ " << phi;
        // Lengths of e_a, e_b (an affine body's slight stretch) do not matter.
        y.head<3>() *= 1.01;
        y.segment<3>(3) *= 0.98;
        EXPECT_NEAR(measure(JointMeasure::TwistAngle, y), tau, 1e-12);
      }
}

TEST(JointMeasures, RelativeAngularVelocityOfTwoRotatingFrames) {
  const Eigen::Matrix3d Fa = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d Fb = Eigen::AngleAxisd(-1.2, Eigen::Vector3d(0, 1, -1).normalized()).toRotationMatrix();
  const Eigen::Vector3d wa(0.3, -1.2, 2.0), wb(-0.5, 0.1, 0.7);
  Eigen::VectorXd y(18), ydot(18);
  for (int k = 0; k < 3; ++k) {
    y.segment<3>(3 * k) = Fa.col(k);
    y.segment<3>(9 + 3 * k) = Fb.col(k);
    ydot.segment<3>(3 * k) = wa.cross(Fa.col(k));
    ydot.segment<3>(9 + 3 * k) = wb.cross(Fb.col(k));
  }
  EXPECT_LT((relative_angular_velocity_jacobian(y) * ydot - (wa - wb)).norm(), 1e-14);
}

TEST(JointTerm, GradientMatchesFiniteDifferencesAndHessianIsPsd) {
  Model model = bodies_model(2, 1);
  // Penalties and limits on every kind, between two bodies and to a fixed body / the world.
  JointModel d = joint(model, JointKind::Distance, 0, 1, Eigen::Vector3d(0.5, 0, 0));
  d.b = end_at(model, 1, Eigen::Vector3d(0.9, 0.2, 0));
  d.rest_length = 0.35;
  d.stiffness = 1e3;
  JointModel bd = joint(model, JointKind::BoundedDistance, 0, -1, Eigen::Vector3d(0, 0.3, 0));
  bd.b = end_at(model, -1, Eigen::Vector3d(0, 1.0, 0));
  bd.lower = 0.68;  // initial 0.7: active (ĝ = 0.05)
  bd.upper = 0.72;
  bd.limit_stiffness = 10;
  JointModel p = joint(model, JointKind::Prismatic, 1, 0, Eigen::Vector3d(0.5, 0.1, 0), Eigen::Vector3d(1, 1, 0).normalized());
  p.stiffness = 1e3;
  p.lower = -0.02;
  p.upper = 0.03;
  JointModel h = joint(model, JointKind::Hinge, 0, 2, Eigen::Vector3d(1.5, 0, 0), Eigen::Vector3d(0, 1, 0));
  h.lower = -0.04;
  h.upper = 0.1;
  // A cone-twist between the two bodies with all three barriers active (bend and twist of the
  // perturbation are a few 1e-3 rad, ĝ = 0.05 rad; checked below).
  JointModel ct = joint(model, JointKind::ConeTwist, 1, 0, Eigen::Vector3d(0.5, 0.1, 0), Eigen::Vector3d(1, 0, 1).normalized());
  ct.swing = 0.03;
  ct.lower = -0.02;
  ct.upper = 0.04;
  model.joints = {d, bd, p, h, ct};
  JointTerm term(model, 0.3);
  ASSERT_EQ(term.potentials().size(), 11u);  // 1 + 2 + (1 + 2) + 2 + 3
  const Eigen::VectorXd q = perturbed(model, 3e-3, 11);
  for (std::size_t k = 8; k < 11; ++k) {
    const auto& [pot, vectors] = term.potentials()[k];
    EXPECT_FALSE(pot.inactive(measure(pot.measure, vectors.gather(q)))) << "cone-twist potential " << k;
  }
  const auto value = [&](const Eigen::VectorXd& x) {
    const Eigen::MatrixX3d none;
    return term.value({x, none});
  };
  const Eigen::MatrixX3d none;
  ASSERT_TRUE(std::isfinite(value(q)));
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  term.add_gradient({q, none}, g);
  EXPECT_LT(relative_error(g, fd_gradient(value, q, 1e-7)), 1e-5);
  BlockHessian H(model.blocks);
  term.add_hessian({q, none}, H);
  const Eigen::MatrixXd Hd = Eigen::MatrixXd(Eigen::SparseMatrix<double>(H.upper().selfadjointView<Eigen::Upper>()));
  EXPECT_GT(min_eigenvalue(Hd), -1e-9 * Hd.norm());

  // Each potential's y-Hessian before the PSD projection: φ'' ∇s∇sᵀ + φ' ∇²s against FD.
  for (const auto& [pot, vectors] : term.potentials()) {
    const Eigen::VectorXd y = vectors.gather(q);
    const auto phi_grad = [&, &pot = pot](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      const MeasureValue m = measure_derivatives(pot.measure, x);
      return pot.first_derivative(m.s) * m.grad;
    };
    if (pot.inactive(measure(pot.measure, y))) continue;  // 0 (and not differentiated)
    const MeasureValue m = measure_derivatives(pot.measure, y);
    const Eigen::MatrixXd H_y = pot.second_derivative(m.s) * m.grad * m.grad.transpose() + pot.first_derivative(m.s) * m.hess;
    EXPECT_LT(relative_error(H_y, fd_jacobian(phi_grad, y, 1e-7)), 1e-5) << "joint " << pot.joint << " wrap " << int(pot.wrap);
  }
}

TEST(JointTerm, LimitsAreInfiniteOutsideAndBoundTheStep) {
  Model model = bodies_model(1);
  JointModel h = joint(model, JointKind::Hinge, 0, -1, Eigen::Vector3d(0, 0, 0));
  h.lower = -0.1;
  h.upper = 0.2;
  model.joints = {h};
  JointTerm term(model, 1.0);
  const Eigen::VectorXd q = model.initial_q();
  const Eigen::MatrixX3d none;
  // Turning body 0 about z by 0.5 rad crosses the upper limit: the step must stop short of it.
  const abd::Vector12d turned = abd::rigid_motion(q.head<12>(), Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 0.5), 1);
  const Eigen::VectorXd dq = Eigen::VectorXd(turned) - q;
  const double alpha = term.max_step({q, none}, dq, none);
  EXPECT_LT(alpha, 1.0);
  EXPECT_GT(alpha, 0.0);
  const Eigen::VectorXd q_end = q + alpha * dq;
  EXPECT_TRUE(std::isfinite(term.value({q_end, none})));
  const Eigen::VectorXd q_far = q + dq;
  EXPECT_FALSE(std::isfinite(term.value({q_far, none})));
}

TEST(ReducedBasis, ChainLoopAndRedundantRows) {
  Model model = bodies_model(3);
  // A chain hanging from the world, closed into a loop back to the world: body0–world ball,
  // body0–body1 hinge, body1–body2 ball, body2–world ball, and the last one repeated.
  model.joints = {joint(model, JointKind::Ball, 0, -1, Eigen::Vector3d(-0.5, 0, 0)),
                  joint(model, JointKind::Hinge, 1, 0, Eigen::Vector3d(0.5, 0.05, 0)),
                  joint(model, JointKind::Ball, 2, 1, Eigen::Vector3d(1.5, 0.15, 0)),
                  joint(model, JointKind::Ball, 2, -1, Eigen::Vector3d(2.5, 0.2, 0)),
                  joint(model, JointKind::Ball, 2, -1, Eigen::Vector3d(2.5, 0.2, 0))};
  const LinearConstraints c = linear_joint_constraints(model);
  ASSERT_EQ(c.rows(), 3 + 6 + 3 + 3 + 3);
  const ReducedBasis basis(model, c);
  EXPECT_EQ(basis.redundant_rows().size(), 3u);
  EXPECT_EQ(basis.reduced_size(), 36 - 15);
  EXPECT_LT(Eigen::MatrixXd(c.C * basis.N()).norm(), 1e-12);
  const Eigen::VectorXd q0 = model.initial_q();
  EXPECT_LT((c.C * q0 - c.d).lpNorm<Eigen::Infinity>(), 1e-12);
  const Eigen::VectorXd q = basis.project(perturbed(model, 0.1, 3));
  EXPECT_LT((c.C * q - c.d).lpNorm<Eigen::Infinity>(), 1e-12);
  // Projection keeps a satisfying configuration.
  EXPECT_LT((basis.project(q0) - q0).norm(), 1e-12);
  // Slaves are translations where possible: the world ball joint of body 0 eliminates its p.
  for (int dof : {0, 1, 2}) EXPECT_NE(std::find(basis.slaves().begin(), basis.slaves().end(), dof), basis.slaves().end());
}

TEST(ReducedBasis, InconsistentJointsAreReportedByName) {
  Model model = bodies_model(1);
  JointModel a = joint(model, JointKind::Ball, 0, -1, Eigen::Vector3d(0, 0, 0));
  JointModel b = a;
  b.name = "contradiction";
  b.b.anchor = Eigen::Vector3d(0, 0.1, 0);  // same body point, another world point
  model.joints = {a, b};
  try {
    ReducedBasis basis(model, linear_joint_constraints(model));
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("contradiction"), std::string::npos) << e.what();
  }
}

TEST(JointTerm, ConeTwistSwingLimitBoundsTheStep) {
  // Bending body 0 by 0.6 rad about x (⟂ the axis z) crosses a swing of 0.4 rad: the step
  // stops short of it, and the energy is +∞ beyond.
  Model model = bodies_model(1);
  JointModel ct = joint(model, JointKind::ConeTwist, 0, -1, Eigen::Vector3d(0, 0, 0));
  ct.swing = 0.4;
  model.joints = {ct};
  JointTerm term(model, 1.0);
  ASSERT_EQ(term.potentials().size(), 1u);
  const Eigen::VectorXd q = model.initial_q();
  const Eigen::MatrixX3d none;
  const abd::Vector12d bent = abd::rigid_motion(q.head<12>(), Eigen::Vector3d::Zero(), Eigen::Vector3d(0.6, 0, 0), 1);
  const Eigen::VectorXd dq = Eigen::VectorXd(bent) - q;
  const double alpha = term.max_step({q, none}, dq, none);
  EXPECT_GT(alpha, 0.0);
  EXPECT_LT(alpha, 0.4 / 0.6);
  EXPECT_TRUE(std::isfinite(term.value({Eigen::VectorXd(q + alpha * dq), none})));
  EXPECT_FALSE(std::isfinite(term.value({Eigen::VectorXd(q + dq), none})));
  // At the initial pose (bend 0, where the bend's derivatives are singular) the inactive
  // barrier adds nothing, and no NaN.
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  term.add_gradient({q, none}, g);
  EXPECT_EQ(g.norm(), 0.0);
}

TEST(DampingTerm, JointDampingIsTheLaggedQuadraticItClaims) {
  Model model = bodies_model(2);
  JointModel h = joint(model, JointKind::Hinge, 0, 1, Eigen::Vector3d(0.5, 0, 0));
  h.damping = 2.0;
  JointModel d = joint(model, JointKind::Distance, 0, 1, Eigen::Vector3d(0.2, 0, 0));
  d.b = end_at(model, 1, Eigen::Vector3d(1.0, 0.3, 0));
  d.damping = 0.5;
  JointModel ball = joint(model, JointKind::Ball, 1, -1, Eigen::Vector3d(1.2, 0, 0));
  ball.damping = 0.3;
  JointModel ct = joint(model, JointKind::ConeTwist, 0, 1, Eigen::Vector3d(0.4, 0.1, 0));
  ct.damping = 0.8;
  model.joints = {h, d, ball, ct};
  DampingTerm term(model);
  const Eigen::VectorXd q_n = perturbed(model, 1e-2, 5);
  term.start_step(q_n, 0.7);
  term.lag_joints();
  ASSERT_FALSE(term.empty());
  const Eigen::MatrixX3d none;
  const Eigen::VectorXd q = perturbed(model, 2e-2, 6);
  const auto value = [&](const Eigen::VectorXd& x) { return term.value({x, none}); };
  EXPECT_EQ(value(q_n), 0.0);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  term.add_gradient({q, none}, g);
  EXPECT_LT(relative_error(g, fd_gradient(value, q)), 1e-6);
  BlockHessian H(model.blocks);
  term.add_hessian({q, none}, H);
  const Eigen::MatrixXd Hd = Eigen::MatrixXd(Eigen::SparseMatrix<double>(H.upper().selfadjointView<Eigen::Upper>()));
  const auto gradient = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd gx = Eigen::VectorXd::Zero(x.size());
    term.add_gradient({x, none}, gx);
    return gx;
  };
  EXPECT_LT(relative_error(Hd, fd_jacobian(gradient, q)), 1e-6);
  // ½ β h c ṡ² h²: the hinge's share for a pure rotation of body 0 about the hinge axis.
  DampingTerm hinge_only(model);
  for (int j = 1; j < 4; ++j) model.joints[j].damping = 0;
  hinge_only.start_step(model.initial_q(), 0.7);
  hinge_only.lag_joints();
  Eigen::VectorXd q1 = model.initial_q();
  const double dtheta = 1e-4;
  q1.head<12>() = abd::rigid_motion(q1.head<12>(), Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, dtheta), 1);
  EXPECT_NEAR(hinge_only.value({q1, none}), 0.5 * 0.7 * 2.0 * dtheta * dtheta, 1e-3 * 0.5 * 0.7 * 2.0 * dtheta * dtheta);
}

TEST(DampingTerm, BallJointDampsTheRelativeAngularVelocity) {
  // ½ β h c |Δφ|² for a rotation Δφ of body 0 relative to body 1 (any axis), none for a common
  // rotation of both bodies (about the same point) or a translation.
  Model model = bodies_model(2);
  JointModel ball = joint(model, JointKind::Ball, 0, 1, Eigen::Vector3d(0.5, 0, 0));
  ball.damping = 1.5;
  model.joints = {ball};
  DampingTerm term(model);
  const Eigen::VectorXd q0 = model.initial_q();
  term.start_step(q0, 0.7);
  term.lag_joints();
  const Eigen::MatrixX3d none;
  const Eigen::Vector3d dphi(1e-4, -2e-4, 0.5e-4);
  Eigen::VectorXd q = q0;
  q.head<12>() = abd::rigid_motion(q0.head<12>(), Eigen::Vector3d(0.3, 0, 0), dphi, 1);
  const double expected = 0.5 * 0.7 * 1.5 * dphi.squaredNorm();
  EXPECT_NEAR(term.value({q, none}), expected, 1e-3 * expected);
  q = q0;
  for (int b = 0; b < 2; ++b) q.segment<12>(12 * b) = abd::rigid_motion(q0.segment<12>(12 * b), Eigen::Vector3d(0.1, 0.2, 0), dphi, 1);
  EXPECT_LT(term.value({q, none}), 1e-6 * expected);
}
