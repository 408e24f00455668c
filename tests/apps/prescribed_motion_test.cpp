/// @file Hard cases of prescribed motion and rigidity: kinematic bodies and prescribed soft
/// nodes follow their paths exactly, and what cannot be honoured stops with a PhysicsError
/// instead of crushing a body (docs/robustness.md).

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include <stiffsoft/libabd/orthogonality_potential.hpp>

#include "scene_helpers.hpp"

namespace stiffsoft {
namespace {

using testing::simulate;

constexpr const char* kSquash = R"({"description": "squash", "gravity": [0, 0, 0], "time": {"dt": 0.01},
  "bodies": [
    {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [0.6, 0.05, 0.6]}, "position": [0, -0.025, 0]},
    {"name": "cube", "model": "soft", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [0, 0.102, 0],
     "mesh_size": 0.07, "material": {"model": "stable_neo_hookean", "young": 1e5, "poisson": 0.4}},
    {"name": "press", "kind": "kinematic", "mesh": {"primitive": "box", "size": [0.6, 0.05, 0.6]}, "position": [0, 0.229, 0],
     "path": [{"duration": 0.5, "velocity": [0, -0.3, 0]}], "velocity": [0, 1, 0]}]})";

TEST(PrescribedMotion, KinematicBodyIsExactlyOnItsPathAfterEveryStepWhileItSquashesASoftCube) {
  Simulation sim = simulate(kSquash);
  const int press = 2;
  const int dof = sim.model().bodies[press].dof;
  double largest_energy = 0;
  for (int k = 0; k < 50; ++k) {
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged) << "step " << s.step << ": " << s.newton.failure;
    largest_energy = std::max(largest_energy, s.elastic_energy);
    const abd::Vector12d on_path = sim.model().kinematic_q(press, sim.time());
    ASSERT_EQ((sim.q().segment<12>(dof) - on_path).cwiseAbs().maxCoeff(), 0.0) << "step " << s.step;
  }
  EXPECT_GT(largest_energy, 1.0) << "the press must have squashed the cube";
}

TEST(PrescribedMotion, PrescribedSoftNodesMoveExactlyAtTheirVelocity) {
  // A soft bar whose right end is pulled at 0.2 m/s while its left end is held.
  Simulation sim = simulate(R"({"description": "pulled bar", "gravity": [0, 0, 0], "time": {"dt": 0.01},
    "bodies": [{"name": "bar", "model": "soft", "mesh": {"primitive": "box", "size": [0.3, 0.05, 0.05]},
      "mesh_size": 0.03, "material": {"young": 1e5, "poisson": 0.3},
      "dirichlet": [{"select": "box", "min": [-1, -1, -1], "max": [-0.149, 1, 1]},
                    {"select": "box", "min": [0.149, -1, -1], "max": [1, 1, 1], "velocity": [0.2, 0, 0]}]}]})");
  const SoftNodes& nodes = sim.model().nodes;
  int pulled = 0;
  for (int k = 0; k < 20; ++k) {
    ASSERT_TRUE(sim.step().newton.converged);
    const Eigen::MatrixX3d x = sim.node_positions();
    for (int i = 0; i < nodes.size(); ++i) {
      if (nodes.motion[i] != Motion::Kinematic) continue;
      pulled += k == 0;
      const Eigen::RowVector3d expected = nodes.X.row(i) + sim.time() * nodes.velocity.row(i);
      ASSERT_EQ((x.row(i) - expected).cwiseAbs().maxCoeff(), 0.0) << "node " << i << " at step " << k + 1;
    }
  }
  EXPECT_GT(pulled, 0);
}

TEST(PrescribedMotion, ACubeCrushedByAKinematicPlateStopsTheRunBeforeItsRigidityBoundIsExceeded) {
  Simulation sim = simulate(testing::read_text(std::string(STIFFSOFT_SOURCE_DIR) + "/tests/apps/data/crushed_cube.json"));
  const int cube = 1, plate = 2;
  std::string error;
  int steps = 0;
  try {
    for (; steps < 100; ++steps) {
      const StepStats s = sim.step();
      EXPECT_LE(s.orthogonality_error, sim.settings().rigidity_bound) << "step " << s.step;
    }
  } catch (const PhysicsError& e) {
    error = e.what();
  }
  std::printf("stopped after %d steps (t = %.3f s): %s\n", steps, sim.time(), error.c_str());
  ASSERT_FALSE(error.empty()) << "the plate must not be able to crush the cube";
  EXPECT_LT(steps, 50) << "the plate meets the cube after ~0.3 s and cannot pass it";
  EXPECT_TRUE(error.find("'cube'") != std::string::npos || error.find("'plate'") != std::string::npos) << error;
  // The state is the last good step: the cube still rigid, the plate on its path.
  EXPECT_LE(abd::orthogonality_error(sim.q().segment<12>(sim.model().bodies[cube].dof)), sim.settings().rigidity_bound);
  const abd::Vector12d on_path = sim.model().kinematic_q(plate, sim.time());
  EXPECT_EQ((sim.q().segment<12>(sim.model().bodies[plate].dof) - on_path).cwiseAbs().maxCoeff(), 0.0);
}

TEST(PrescribedMotion, TheRigidityBoundIsChecked) {
  // A box dropped on the floor deforms by ~1e-6 on impact: a bound of 1e-9 stops the run
  // with an error naming the box.
  Simulation sim = simulate(R"({"description": "drop", "time": {"dt": 0.01}, "solver": {"rigidity_bound": 1e-9},
    "bodies": [
      {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [1, 0.05, 1]}, "position": [0, -0.025, 0]},
      {"name": "box", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, 0.06, 0]}]})");
  try {
    for (int k = 0; k < 100; ++k) sim.step();
    FAIL() << "no step exceeded a rigidity bound of 1e-9";
  } catch (const PhysicsError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("affine body 'box': rigidity error"), std::string::npos) << text;
    EXPECT_NE(text.find("rigidity_bound"), std::string::npos) << text;
  }
}

TEST(PrescribedMotion, TheCommandStopsWithExitCode3AndKeepsItsFrames) {
  const auto out = testing::temporary_folder("crushed_cube");
  const int code = testing::run_stiffsoft(
      "run " + std::string(STIFFSOFT_SOURCE_DIR) + "/tests/apps/data/crushed_cube.json -o " + (out / "run").string(),
      out / "log.txt");
  const std::string log = testing::read_text(out / "log.txt");
  std::printf("%s", log.c_str());
  EXPECT_EQ(code, 3);
  EXPECT_NE(log.find("stopped: wrote"), std::string::npos) << log;
  EXPECT_TRUE(std::filesystem::exists(out / "run" / "crushed_cube.pvd"));
  EXPECT_GT(testing::csv_column(out / "run" / "stats.csv", "step").size(), 10u);
  std::filesystem::remove_all(out);
}

TEST(PrescribedMotion, APressDrivenThroughASoftCubeStopsWithAnErrorNamingItAndLogsTheInversions) {
  const auto out = testing::temporary_folder("press_through");
  const int code = testing::run_stiffsoft("run " + std::string(STIFFSOFT_SOURCE_DIR) +
                                              "/tests/apps/data/press_through_soft_cube.json -o " + (out / "run").string(),
                                          out / "log.txt");
  const std::string log = testing::read_text(out / "log.txt");
  EXPECT_EQ(code, 3) << log;
  EXPECT_NE(log.find("kinematic body 'press' cannot follow its path"), std::string::npos) << log;
  EXPECT_NE(log.find("soft body 'cube' has"), std::string::npos) << log;
  EXPECT_NE(log.find("inverted tetrahedra in"), std::string::npos) << log;
  // Logged when they appear (and again after they were gone), not every step.
  std::size_t warnings = 0;
  for (std::size_t at = log.find("inverted tetrahedra (det F"); at != std::string::npos;
       at = log.find("inverted tetrahedra (det F", at + 1))
    ++warnings;
  const std::vector<double> inverted = testing::csv_column(out / "run" / "stats.csv", "inverted_tets");
  const long steps_inverted = std::count_if(inverted.begin(), inverted.end(), [](double n) { return n > 0; });
  std::printf("%zu inversion warnings for %ld steps with inverted tetrahedra\n", warnings, steps_inverted);
  EXPECT_GE(warnings, 1u);
  EXPECT_LT(long(warnings), steps_inverted);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace stiffsoft
