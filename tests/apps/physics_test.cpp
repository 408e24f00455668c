/// @file Physics against the analytic answers of validation.md, on small inline scenes.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include <stiffsoft/libabd/affine_body.hpp>
#include "scene_helpers.hpp"

using namespace stiffsoft;
using stiffsoft::testing::simulate;

namespace {

/// World angular momentum of dynamic body b about the origin: m p × ṗ + Σ ε_ijk (A S Ȧᵀ)_jk,
/// S = ρ∫x̄x̄ᵀ (the lower-right 3×3 of M when x̄ is centred).
Eigen::Vector3d angular_momentum(const Simulation& sim, int b) {
  const BodyModel& body = sim.model().bodies[b];
  const abd::Vector12d q = sim.q().segment<12>(body.dof), qd = sim.qdot().segment<12>(body.dof);
  const Eigen::Matrix3d S = body.M.block<3, 3>(3, 3);
  const Eigen::Matrix3d C = abd::affine_matrix(q) * S * abd::affine_matrix(qd).transpose();
  const Eigen::Vector3d spin(C(1, 2) - C(2, 1), C(2, 0) - C(0, 2), C(0, 1) - C(1, 0));
  return body.mass * q.head<3>().cross(qd.head<3>()) + spin;
}

std::string free_box(const std::string& integrator, double dt) {
  return R"({"description": "free flight", "gravity": [0, 0, 0],
    "time": {"dt": )" + std::to_string(dt) + R"(, "duration": 1, "integrator": ")" + integrator + R"("},
    "solver": {"tolerance": 1e-7},
    "bodies": [{"name": "box", "mesh": {"primitive": "box", "size": [1, 0.5, 0.1]},
                "velocity": [1, 2, -0.5], "angular_velocity": [0, 0, 3]}]})";
}

}  // namespace

TEST(FreeFlight, BackwardEulerKeepsLinearMomentumExactly) {
  Simulation sim = simulate(free_box("backward_euler", 0.01));
  const Eigen::Vector3d p0 = sim.model().bodies[0].mass * sim.qdot().head<3>();
  for (int k = 0; k < 50; ++k) {
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged) << s.newton.failure;
    EXPECT_LT((s.linear_momentum - p0).norm(), 1e-9 * p0.norm());
  }
}

TEST(FreeFlight, AngularMomentumIsKeptToTheIntegratorsOrder) {
  // Rotation about the box's stable major axis (z): BDF-2's error shrinks ~4× per halving of h.
  // Newton's tolerance is tight here: the default ε_d = 1e-2 L/s leaves a velocity error of
  // order ε_d per step, which would swamp the integrator's own error.
  double previous = 0;
  for (double dt : {0.004, 0.002}) {
    Simulation sim = simulate(free_box("bdf2", dt));
    const Eigen::Vector3d L0 = angular_momentum(sim, 0);
    for (int k = 0; k < int(std::lround(0.2 / dt)); ++k) ASSERT_TRUE(sim.step().newton.converged);
    const double error = (angular_momentum(sim, 0) - L0).norm() / L0.norm();
    std::printf("BDF-2, h = %g: relative angular-momentum drift over 0.2 s = %.3e\n", dt, error);
    EXPECT_LT(error, 1e-3);
    if (previous > 0) EXPECT_LT(error, previous / 2.5) << "no second-order convergence";
    previous = error;
  }
}

TEST(FreeFlight, OrthogonalityErrorStaysSmall) {
  Simulation sim = simulate(free_box("backward_euler", 0.01));
  for (int k = 0; k < 50; ++k) EXPECT_LT(sim.step().orthogonality_error, 1e-3);
}

TEST(KinematicBody, FollowsItsPrescribedMotionAndPushesABox) {
  // A kinematic paddle moving at 1 m/s along x and spinning slowly about y sweeps into a free box
  // (no gravity): it follows its path, and the box ends up ahead of it, moving.
  Simulation sim = simulate(R"({"description": "kinematic paddle", "gravity": [0, 0, 0],
    "time": {"dt": 0.01, "duration": 1},
    "bodies": [
      {"name": "paddle", "kind": "kinematic", "mesh": {"primitive": "box", "size": [0.1, 0.5, 0.5]},
       "velocity": [1, 0, 0], "angular_velocity": [0, 0.2, 0]},
      {"name": "box", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [0.3, 0, 0]}]})");
  const BodyModel& paddle = sim.model().bodies[0];
  for (int k = 0; k < 50; ++k) ASSERT_TRUE(sim.step().newton.converged);
  const abd::Vector12d target = abd::rigid_motion(paddle.q0, paddle.v0, paddle.w0, sim.time());
  const abd::Vector12d q = sim.q().segment<12>(paddle.dof);
  std::printf("paddle deviation from its path after %.2f s: %.2e m, %.2e (A)\n", sim.time(),
              (q.head<3>() - target.head<3>()).norm(), (q.tail<9>() - target.tail<9>()).norm());
  EXPECT_LT((q.head<3>() - target.head<3>()).norm(), 1e-3);
  EXPECT_LT((q.tail<9>() - target.tail<9>()).norm(), 1e-3);
  const int box = sim.model().bodies[1].dof;
  EXPECT_GT(sim.q()[box], q[0] + 0.05 + 0.1) << "the box must stay ahead of the paddle";
  EXPECT_GT(sim.qdot()[box], 0.5) << "the box must have been pushed";
}
