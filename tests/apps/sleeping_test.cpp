/// @file Sleeping bodies (solver.sleep_time, coupling/solver/sleeping.hpp): a resting stack falls
/// asleep, then stays exactly where it is at no Newton iteration, and near where it rests awake;
/// a box dropped on it wakes what it reaches before it lands, nothing sleeps in flight and no
/// body faster than v_s comes within d̂ of a held one in a kept step; a body at rest sleeps while
/// another still slides on what it rests on; what it changes before the first body sleeps is
/// nothing; a state taken while it sleeps continues the same; bodies joined by a joint sleep and
/// wake together, and a body hanging on a joint sleeps.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "scene_helpers.hpp"

namespace stiffsoft::testing {
namespace {

/// Two 0.2-m cubes stacked 5 mm apart on a fixed ground (h = 0.01, μ = 0.3), `sleep` seconds to
/// fall asleep (0: never), and, with `drop`, a third cube 0.6 m above them.
std::string stack_scene(double sleep, bool drop) {
  const auto cube = [](const std::string& name, double y) {
    return R"({"name": ")" + name +
           R"(", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [0, )" +
           std::to_string(y) + R"(, 0]})";
  };
  return R"({"description": "a stack for sleeping", "time": {"dt": 0.01, "duration": 3}, "contact": {"mu": 0.3},
    "solver": {"sleep_time": )" +
         std::to_string(sleep) + R"(},
    "bodies": [{"name": "ground", "kind": "fixed", "mesh": {"primitive": "box", "size": [1, 0.1, 1]},
                "position": [0, -0.05, 0]}, )" +
         cube("lower", 0.105) + ", " + cube("upper", 0.31) + (drop ? ", " + cube("dropped", 0.91) : "") +
         "]}";
}

/// The largest distance between the affine bodies' DOFs of two runs' q (m: positions and the
/// columns of A times 1 m).
double largest_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

TEST(Sleeping, ARestingStackFallsAsleepStaysPutAndRestsWhereItWouldAwake) {
  Simulation awake = simulate(stack_scene(0, false), "awake");
  Simulation sleeping = simulate(stack_scene(0.3, false), "sleeping");
  int first_asleep = -1;
  Eigen::VectorXd q_asleep;
  for (int k = 0; k < 300; ++k) {
    const StepStats a = awake.step();
    const StepStats s = sleeping.step();
    ASSERT_TRUE(a.newton.converged && s.newton.converged) << "step " << k;
    ASSERT_GT(s.smallest_distance, 0) << "step " << k;
    if (first_asleep < 0) {
      // Nothing differs before the first body sleeps.
      EXPECT_EQ(a.newton.iterations, s.newton.iterations) << "step " << k;
      ASSERT_EQ(awake.q(), sleeping.q()) << "step " << k;
    }
    if (first_asleep < 0 && s.sleeping_bodies == 2) {
      first_asleep = k;
      q_asleep = sleeping.q();
      EXPECT_EQ(sleeping.qdot().cwiseAbs().maxCoeff(), 0.0) << "a sleeping body has no velocity";
    } else if (first_asleep >= 0) {
      EXPECT_EQ(s.sleeping_bodies, 2) << "step " << k << ": nothing woke the stack";
      EXPECT_EQ(s.newton.iterations, 0) << "step " << k;
      EXPECT_EQ(s.contacts, 0) << "step " << k << ": a contact among still bodies was computed";
    }
  }
  ASSERT_GE(first_asleep, 30) << "the stack slept before it had rested 0.3 s";
  ASSERT_LT(first_asleep, 200) << "the stack never fell asleep";
  EXPECT_EQ(sleeping.q(), q_asleep) << "a sleeping stack moved";
  // Awake, the stack goes on settling: by less than the speed it slept below times the time
  // since, and, here, by less than a millimetre (and a milliradian).
  const double since = 0.01 * (300 - first_asleep);
  const double speed = sleeping.settings().sleep_speed.value_or(sleeping.settings().tolerance);
  EXPECT_LT(largest_difference(awake.q(), sleeping.q()), speed * since);
  EXPECT_LT(largest_difference(awake.q(), sleeping.q()), 1e-3);  // 0.16 mm when written
}

/// Body b's axis-aligned box over the rows of x, grown by r.
std::pair<Eigen::Array3d, Eigen::Array3d> body_box(const Model& model, int b, const Eigen::MatrixX3d& x, double r) {
  const BodyModel& body = model.bodies[b];
  const Eigen::MatrixX3d rows = x.middleRows(body.vertex_begin, body.vertex_end - body.vertex_begin);
  return {rows.colwise().minCoeff().transpose().array() - r, rows.colwise().maxCoeff().transpose().array() + r};
}

/// Whether any body asleep through the step from x_n to x (in `before` and `after`) has within d̂
/// of its box the box swept by a body that moved faster than v_s in the step.
bool a_mover_met_a_sleeper(const Simulation& sim, const Sleeping::State& before, const Sleeping::State& after,
                           const Eigen::MatrixX3d& x_n, const Eigen::MatrixX3d& x) {
  const Model& model = sim.model();
  const double dhat = sim.settings().dhat, h = sim.settings().h;
  const double speed = sim.settings().sleep_speed.value_or(sim.settings().tolerance);
  for (int m = 0; m < int(model.bodies.size()); ++m) {
    const BodyModel& body = model.bodies[m];
    if (before.asleep[m] >= 0 || body.dof < 0) continue;
    double move = 0;
    for (int v = body.vertex_begin; v < body.vertex_end; ++v) move = std::max(move, (x.row(v) - x_n.row(v)).norm());
    if (move <= speed * h) continue;
    const auto [lo0, hi0] = body_box(model, m, x_n, dhat);
    const auto [lo1, hi1] = body_box(model, m, x, dhat);
    for (int b = 0; b < int(model.bodies.size()); ++b) {
      if (before.asleep[b] < 0 || after.asleep[b] < 0) continue;
      const auto [lo, hi] = body_box(model, b, x_n, dhat);
      if ((lo0.min(lo1) <= hi).all() && (lo <= hi0.max(hi1)).all()) return true;
    }
  }
  return false;
}

/// One step of `sim`, checked as every step with sleeping bodies must be: converged,
/// intersection-free, no body faster than v_s within d̂ of a sleeping one (a_mover_met_a_sleeper),
/// no sleeping body moved. `s` gets the step's statistics.
::testing::AssertionResult checked_step(Simulation& sim, StepStats& s) {
  const Sleeping::State before = sim.state().sleeping;
  const Eigen::MatrixX3d x_n = sim.model().surface(sim.q());
  const Eigen::VectorXd q_n = sim.q();
  s = sim.step();
  if (!s.newton.converged) return ::testing::AssertionFailure() << "Newton did not converge";
  if (!(s.smallest_distance > 0)) return ::testing::AssertionFailure() << "surfaces touch or intersect";
  const Sleeping::State after = sim.state().sleeping;
  if (a_mover_met_a_sleeper(sim, before, after, x_n, sim.model().surface(sim.q())))
    return ::testing::AssertionFailure()
           << "a body faster than v_s came within d̂ of a sleeping one and the step was kept";
  for (int b = 0; b < int(sim.model().bodies.size()); ++b) {
    const int dof = sim.model().bodies[b].dof;
    if (dof >= 0 && before.asleep[b] >= 0 && after.asleep[b] >= 0 && sim.q().segment<12>(dof) != q_n.segment<12>(dof))
      return ::testing::AssertionFailure() << "sleeping body " << b << " moved";
  }
  return ::testing::AssertionSuccess();
}

TEST(Sleeping, ADroppedBoxWakesWhatItReachesAndNoMovingBodyEverMeetsAHeldOne) {
  Simulation sim = simulate(stack_scene(0.2, true), "drop");
  Simulation awake = simulate(stack_scene(0, true), "drop_awake");
  const int upper = 2, dropped = 3;
  const int dof = sim.model().bodies[dropped].dof;
  int slept = -1, woke = -1, landed = -1;
  double top_speed_after = 0, awake_top_speed_after = 0;
  for (int k = 0; k < 300; ++k) {
    StepStats s;
    ASSERT_TRUE(checked_step(sim, s)) << "step " << k;
    awake.step();
    const Sleeping::State after = sim.state().sleeping;
    const bool dropped_in_contact = sim.q()[dof + 1] < 0.31 + 0.2 + 2 * sim.settings().dhat;
    if (landed < 0 && dropped_in_contact) landed = k;
    if (landed < 0) EXPECT_LT(after.asleep[dropped], 0) << "step " << k << ": the falling box slept";
    // While the stack sleeps and the box falls, the contacts among still bodies (the cubes and
    // the ground) are left out: there is none to compute.
    if (slept >= 0 && woke < 0 && s.sleeping_bodies == 2) EXPECT_EQ(s.contacts, 0) << "step " << k;
    if (slept < 0 && s.sleeping_bodies == 2) slept = k;
    if (slept >= 0 && woke < 0 && after.asleep[upper] < 0) woke = k;
    if (landed >= 0 && k < landed + 10) {
      top_speed_after = std::max(top_speed_after, sim.qdot().segment<3>(sim.model().bodies[upper].dof).norm());
      awake_top_speed_after =
          std::max(awake_top_speed_after, awake.qdot().segment<3>(awake.model().bodies[upper].dof).norm());
    }
  }
  ASSERT_GE(slept, 0) << "the stack never slept before the box arrived";
  ASSERT_GE(landed, 0) << "the dropped box never reached the stack";
  ASSERT_GE(woke, 0) << "the upper cube never woke";
  EXPECT_LT(slept, landed);
  EXPECT_LE(woke, landed) << "the upper cube woke only after the box had landed on it";
  // The landing moves the upper cube as it moves the awake stack's.
  EXPECT_NEAR(top_speed_after, awake_top_speed_after, 0.1 * awake_top_speed_after);
}

/// A 2 m slab on a fixed ground (h = 0.01, μ = 0.05), a 0.2-m cube resting on its left end and a
/// box sliding on its right end at 0.4 m/s, which friction stops in about 0.8 s.
std::string slab_scene(double sleep) {
  return R"({"description": "a cube resting beside a sliding box", "time": {"dt": 0.01, "duration": 2},
    "contact": {"mu": 0.05, "dhat": 0.001}, "solver": {"sleep_time": )" +
         std::to_string(sleep) + R"(},
    "bodies": [{"name": "ground", "kind": "fixed", "mesh": {"primitive": "box", "size": [3, 0.1, 1]},
                "position": [0, -0.05, 0]},
               {"name": "slab", "mesh": {"primitive": "box", "size": [2, 0.05, 0.6]}, "position": [0, 0.027, 0]},
               {"name": "cube", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [-0.8, 0.154, 0]},
               {"name": "slider", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [0.2, 0.154, 0],
                "velocity": [0.4, 0, 0]}]})";
}

TEST(Sleeping, ABodyAtRestSleepsWhileAnotherMovesOnWhatItRestsOn) {
  Simulation sim = simulate(slab_scene(0.2), "slab");
  Simulation awake = simulate(slab_scene(0), "slab_awake");
  const int slab = 1, cube = 2, slider = 3;
  const double speed = sim.settings().sleep_speed.value_or(sim.settings().tolerance);
  int cube_slept_while_sliding = 0;
  for (int k = 0; k < 200; ++k) {
    const StepStats s = sim.step();
    awake.step();
    ASSERT_TRUE(s.newton.converged) << "step " << k;
    ASSERT_GT(s.smallest_distance, 0) << "step " << k;
    const Sleeping::State state = sim.state().sleeping;
    const bool sliding = sim.qdot().segment<3>(sim.model().bodies[slider].dof).norm() > speed;
    if (sliding) {
      EXPECT_LT(state.asleep[slab], 0) << "step " << k << ": the slab slept under the sliding box";
      EXPECT_LT(state.asleep[slider], 0) << "step " << k;
    }
    cube_slept_while_sliding += sliding && state.asleep[cube] >= 0;
  }
  EXPECT_GT(cube_slept_while_sliding, 20) << "the cube did not sleep while the box slid";
  for (int b : {slab, cube, slider}) EXPECT_GE(sim.state().sleeping.asleep[b], 0) << "body " << b << " awake at the end";
  // Where the awake run ends: the slider's stop and the cube's rest within a millimetre.
  EXPECT_LT(largest_difference(awake.q(), sim.q()), 1e-3);
}

TEST(Sleeping, AStateTakenWhileItSleepsContinuesTheSame) {
  Simulation first = simulate(stack_scene(0.2, true), "first");
  for (int k = 0; k < 60; ++k) first.step();
  ASSERT_GT(first.step().sleeping_bodies, 0) << "take the state while the stack sleeps";
  const SimulationState state = first.state();
  Simulation second = simulate(stack_scene(0.2, true), "second");
  second.restore(state);
  for (int k = 0; k < 60; ++k) {
    const StepStats a = first.step();
    const StepStats b = second.step();
    ASSERT_EQ(a.sleeping_bodies, b.sleeping_bodies) << "step " << k;
    ASSERT_EQ(first.q(), second.q()) << "step " << k;
  }
}

/// Two 0.2-m cubes 1 cm apart joined by a ball joint between them, 5 mm above a fixed ground
/// (h = 0.01, μ = 0.3); a third hanging still 2 m away from a ball joint to the world 0.2 m above
/// its centre; and a cube dropped from 1.3 m above the ground onto the right one's outer half.
std::string jointed_scene(double sleep) {
  return R"({"description": "a jointed pair and a hanging cube", "time": {"dt": 0.01, "duration": 3},
    "contact": {"mu": 0.3}, "solver": {"sleep_time": )" +
         std::to_string(sleep) + R"(},
    "bodies": [{"name": "ground", "kind": "fixed", "mesh": {"primitive": "box", "size": [5, 0.1, 1]},
                "position": [0, -0.05, 0]},
               {"name": "left", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [-0.105, 0.105, 0]},
               {"name": "right", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [0.105, 0.105, 0]},
               {"name": "lamp", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [2, 1, 0]},
               {"name": "dropped", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [0.15, 1.4, 0]}],
    "joints": [{"name": "pair", "kind": "ball", "body_a": "left", "body_b": "right", "anchor": [0, 0.105, 0]},
               {"name": "hook", "kind": "ball", "body_a": "lamp", "body_b": "world", "anchor": [2, 1.2, 0]}]})";
}

TEST(Sleeping, JointedBodiesSleepAndWakeTogetherAndAHangingBodySleeps) {
  Simulation sim = simulate(jointed_scene(0.2), "jointed");
  Simulation awake = simulate(jointed_scene(0), "jointed_awake");
  const int left = 1, right = 2, lamp = 3, dropped = 4;
  int slept = -1, woke = -1, landed = -1, lamp_slept = -1, all_slept = -1;
  for (int k = 0; k < 300; ++k) {
    StepStats s;
    ASSERT_TRUE(checked_step(sim, s)) << "step " << k;
    awake.step();
    ASSERT_LT(s.joint_error, 1e-9) << "step " << k;
    const Sleeping::State after = sim.state().sleeping;
    if (s.sleeping_bodies == 0 && slept < 0 && lamp_slept < 0)
      ASSERT_EQ(awake.q(), sim.q()) << "step " << k << ": a run differs before anything sleeps";
    ASSERT_EQ(after.asleep[left] >= 0, after.asleep[right] >= 0) << "step " << k << ": the joined pair split";
    const int ddof = sim.model().bodies[dropped].dof;
    if (landed < 0 && sim.q()[ddof + 1] < 0.2 + 0.1 + 2 * sim.settings().dhat) landed = k;
    if (lamp_slept < 0 && after.asleep[lamp] >= 0) lamp_slept = k;
    if (lamp_slept >= 0) EXPECT_GE(after.asleep[lamp], 0) << "step " << k << ": the lamp woke, nothing reaches it";
    if (slept < 0 && after.asleep[left] >= 0) slept = k;
    if (slept >= 0 && woke < 0 && after.asleep[left] < 0) woke = k;
    if (s.sleeping_bodies == 4) {
      if (all_slept < 0) all_slept = k;
      else EXPECT_EQ(s.newton.iterations, 0) << "step " << k;
    }
  }
  // It rests from the first step (its joint holds it), so it sleeps at the end of the 20th.
  ASSERT_GE(lamp_slept, 19) << "the hanging cube never slept, or before it had rested 0.2 s";
  ASSERT_GE(slept, 0) << "the pair never slept before the box arrived";
  ASSERT_GE(landed, 0) << "the dropped box never reached the pair";
  ASSERT_GE(woke, 0) << "the pair never woke";
  EXPECT_LT(slept, landed);
  EXPECT_LE(woke, landed) << "the pair woke only after the box had landed";
  EXPECT_GT(all_slept, landed) << "the pair and the dropped box never slept again";
}

}  // namespace
}  // namespace stiffsoft::testing
