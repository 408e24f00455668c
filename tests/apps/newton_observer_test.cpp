/// @file Simulation::observe_newton (what tools/newton_probe builds on): the observer sees
/// every Newton direction with the iterate's gradient and the matrix the direction solves, and
/// evaluating the terms elsewhere inside it (as the probe does) leaves the run unchanged.

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "scene_helpers.hpp"

using namespace stiffsoft;

namespace {

/// Two boxes dropped onto a floor and onto each other, with friction: contacts, CCD-limited
/// and revised directions within a few steps.
const char* kScene = R"({"description": "observer", "time": {"dt": 0.01}, "contact": {"dhat": 0.001, "mu": 0.4},
  "bodies": [
    {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [1.0, 0.1, 1.0]}, "position": [0, -0.05, 0]},
    {"name": "low", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, 0.052, 0],
     "rotation_deg": [0, 20, 0], "velocity": [0.3, -1, 0]},
    {"name": "high", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0.02, 0.16, 0.01],
     "rotation_deg": [5, 0, 0], "velocity": [0, -1.5, 0]}]})";

constexpr int kSteps = 15;

}  // namespace

TEST(NewtonObserver, SeesEveryDirectionAndProbingChangesNothing) {
  Simulation plain = stiffsoft::testing::simulate(kScene);
  std::vector<int> iterations;
  for (int k = 0; k < kSteps; ++k) iterations.push_back(plain.step().newton.iterations);

  Simulation observed = stiffsoft::testing::simulate(kScene);
  int directions = 0, expected_iteration = 0;
  double worst_gradient = 0, worst_solve = 0;
  observed.observe_newton([&](const NewtonIterate& it) {
    ++directions;
    EXPECT_EQ(it.iteration, expected_iteration++);
    // g is the gradient of the terms at the iterate, and p solves H p = −g (unless springs on
    // pairs entering d̂ changed it: EnteringSprings, tested in entering_springs_test.cpp).
    Eigen::VectorXd g = Eigen::VectorXd::Zero(it.c.q.size());
    for (const EnergyTerm* t : it.terms) t->add_gradient(it.c, g);
    worst_gradient = std::max(worst_gradient, (g - it.g).norm() / std::max(g.norm(), 1e-300));
    if (it.springs == 0)
      worst_solve = std::max(worst_solve, (it.H.multiply(it.p) + it.g).norm() / std::max(it.g.norm(), 1e-300));
    EXPECT_GT(it.alpha, 0.0);
    EXPECT_LE(it.alpha, 1.0);
    // Evaluate somewhere else, then leave the terms at the iterate, as the contract asks.
    const Eigen::VectorXd q_far = it.c.q + 0.5 * it.p;
    const Eigen::MatrixX3d x_far = it.model.surface(q_far);
    for (EnergyTerm* t : it.terms) t->update({q_far, x_far});
    for (const EnergyTerm* t : it.terms) (void)t->value({q_far, x_far});
    for (EnergyTerm* t : it.terms) t->update(it.c);
  });
  int total = 0, contact_steps = 0, ccd_limited = 0;
  for (int k = 0; k < kSteps; ++k) {
    expected_iteration = 0;  // each step is one minimisation (friction lagged once)
    const StepStats s = observed.step();
    EXPECT_EQ(s.newton.iterations, iterations[k]) << "step " << k + 1;
    total += s.newton.iterations;
    contact_steps += s.contacts > 0;
    ccd_limited += s.newton.ccd_limited_iterations;
  }
  std::printf("%d directions in %d steps, %d with contacts, %d CCD-limited\n", total, kSteps, contact_steps, ccd_limited);
  EXPECT_GE(contact_steps, kSteps / 2);  // the observer saw contact states
  EXPECT_EQ(directions, total);
  EXPECT_LT(worst_gradient, 1e-12);
  EXPECT_LT(worst_solve, 1e-8);
  EXPECT_EQ(observed.q(), plain.q());  // bit for bit
  EXPECT_GT(observed.state().step, 0);
}
