/// @file Sleeping bodies (solver.sleep_time, coupling/solver/sleeping.hpp): a resting stack falls
/// asleep, then stays exactly where it is at no Newton iteration, and near where it rests awake;
/// a box dropped on it wakes it before it lands and nothing sleeps in flight; what it changes
/// before the first body sleeps is nothing; a state taken while it sleeps continues the same; a
/// scene with joints is refused.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

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
  int first_asleep = -1, contacts_asleep = 0;
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
      contacts_asleep = s.contacts;
      EXPECT_EQ(sleeping.qdot().cwiseAbs().maxCoeff(), 0.0) << "a sleeping body has no velocity";
    } else if (first_asleep >= 0) {
      EXPECT_EQ(s.sleeping_bodies, 2) << "step " << k << ": nothing woke the stack";
      EXPECT_EQ(s.newton.iterations, 0) << "step " << k;
      EXPECT_EQ(s.contacts, contacts_asleep) << "step " << k;
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

TEST(Sleeping, ADroppedBoxWakesTheStackBeforeItLandsAndNothingSleepsInFlight) {
  Simulation sim = simulate(stack_scene(0.2, true), "drop");
  const int dropped = 3;
  const int dof = sim.model().bodies[dropped].dof;
  int slept = -1, woke = -1, landed = -1;
  double top_speed_after = 0;
  for (int k = 0; k < 300; ++k) {
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged) << "step " << k;
    ASSERT_GT(s.smallest_distance, 0) << "step " << k;
    const bool dropped_in_contact = sim.q()[dof + 1] < 0.31 + 0.2 + 2 * sim.settings().dhat;
    if (landed < 0 && dropped_in_contact) landed = k;
    if (landed < 0) EXPECT_LE(s.sleeping_bodies, 2) << "step " << k << ": the falling box slept";
    // While the stack sleeps and the box falls, the contacts among still bodies (the cubes and
    // the ground) are left out: there is none to compute.
    if (slept >= 0 && woke < 0 && s.sleeping_bodies == 2) EXPECT_EQ(s.contacts, 0) << "step " << k;
    if (slept < 0 && s.sleeping_bodies == 2) slept = k;
    if (slept >= 0 && woke < 0 && s.sleeping_bodies == 0) woke = k;
    if (landed >= 0 && k < landed + 10)
      top_speed_after = std::max(top_speed_after, sim.qdot().segment<3>(sim.model().bodies[2].dof).norm());
  }
  ASSERT_GE(slept, 0) << "the stack never slept before the box arrived";
  ASSERT_GE(landed, 0) << "the dropped box never reached the stack";
  ASSERT_GE(woke, 0) << "the stack never woke";
  EXPECT_LT(slept, landed);
  EXPECT_LE(woke, landed) << "the stack woke only after the box had landed on it";
  EXPECT_GT(top_speed_after, 0.01) << "the landing did not move the upper cube";
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

TEST(Sleeping, ASceneWithJointsIsRefused) {
  const std::string json =
      R"({"description": "a pendulum", "time": {"dt": 0.01, "duration": 1}, "solver": {"sleep_time": 0.5},
    "bodies": [{"name": "a", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [0, 1, 0]}],
    "joints": [{"name": "pin", "kind": "ball", "body_a": "a", "anchor": [0, 1.1, 0]}]})";
  try {
    simulate(json, "jointed");
    FAIL() << "a scene with joints and sleep_time was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.json_path(), "solver.sleep_time");
    EXPECT_NE(std::string(e.what()).find("joints"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stiffsoft::testing
