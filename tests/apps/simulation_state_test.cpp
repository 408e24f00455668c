/// @file Simulation::state / restore: a run continued in a second Simulation from a saved state
/// is the same run.

#include <gtest/gtest.h>

#include "scene_helpers.hpp"

using namespace stiffsoft;

namespace {

Simulation light_pile() {
  const std::string file = STIFFSOFT_SOURCE_DIR "/scenes/light.json";
  PreparedScene p = prepare_scene(file);
  p.settings.balance_kappa = true;  // the state then carries a balanced κ and its flag
  return Simulation(std::move(p.model), p.settings);
}

}  // namespace

TEST(SimulationState, RestoredRunContinuesTheSameTrajectory) {
  // The light pile's bodies land on the floor after about 25 steps of 1/240 s: the saved state
  // is in contact, with friction and an already balanced κ.
  const int before = 35, after = 15;
  Simulation whole = light_pile();
  for (int k = 0; k < before + after; ++k) whole.step();

  Simulation first = light_pile();
  int contacts = 0;
  for (int k = 0; k < before; ++k) contacts = first.step().contacts;
  const SimulationState saved = first.state();
  ASSERT_GT(contacts, 0) << "the state to save should be in contact";
  ASSERT_TRUE(saved.kappa_balanced);
  EXPECT_EQ(saved.step, before);

  Simulation second = light_pile();
  second.restore(saved);
  for (int k = 0; k < after; ++k) second.step();
  EXPECT_DOUBLE_EQ(second.time(), whole.time());
  const double apart = (second.surface() - whole.surface()).rowwise().norm().maxCoeff();
  // Same arithmetic on the same state, up to the order of parallel sums.
  EXPECT_LT(apart, 1e-9) << "m between the continued and the uninterrupted run";
}

TEST(SimulationState, RestoringAnotherModelsStateIsRefused) {
  Simulation sim = light_pile();
  SimulationState wrong = sim.state();
  wrong.q.resize(wrong.q.size() - 12);
  EXPECT_THROW(sim.restore(wrong), std::invalid_argument);
}
