/// @file Soft and affine bodies together: momentum through a free collision, squash and
/// recover, the `auto` model choice, kinematic paths, and clear errors for bad soft input.

#include <gtest/gtest.h>

#include <cstdio>

#include "scene_helpers.hpp"

using namespace stiffsoft;
using namespace stiffsoft::testing;
namespace fs = std::filesystem;

namespace {

/// Total linear momentum Σ m v of every dynamic body and node (kg·m/s).
Eigen::Vector3d momentum(const Simulation& sim) {
  const Model& model = sim.model();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (const BodyModel& body : model.bodies)
    if (body.dof >= 0 && body.motion == Motion::Dynamic) p += body.mass * sim.qdot().segment<3>(body.dof);
  for (int i = 0; i < model.nodes.size(); ++i)
    if (model.nodes.motion[i] == Motion::Dynamic) p += model.nodes.mass[i] * sim.qdot().segment<3>(model.nodes.dof[i]);
  return p;
}

}  // namespace

TEST(Hybrid, FreeCollisionOfSoftAndAffineBodyKeepsLinearMomentum) {
  // No gravity, no friction: a soft ball flies into a resting affine box, squashes against it
  // and both fly on. Every force is internal, so Σ m v stays what it was (backward Euler keeps
  // linear momentum exactly; what remains is Newton's tolerance).
  Simulation sim = simulate(R"({"description": "soft ball hits affine box", "gravity": [0, 0, 0],
    "time": {"dt": 0.005}, "solver": {"tolerance": 1e-5},
    "bodies": [
      {"name": "ball", "model": "soft", "mesh": {"primitive": "sphere", "radius": 0.1}, "mesh_size": 0.05,
       "material": {"young": 1e5, "poisson": 0.4}, "position": [-0.3, 0.02, 0], "velocity": [2, 0, 0]},
      {"name": "box", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [0.0, 0, 0], "density": 500}]})");
  const Eigen::Vector3d p0 = momentum(sim);
  int steps_in_contact = 0;
  for (int k = 0; k < 120; ++k) {
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged) << "step " << s.step << ": " << s.newton.failure;
    ASSERT_EQ(s.inverted_tets, 0);
    steps_in_contact += s.contacts > 0;
  }
  const Eigen::Vector3d p1 = momentum(sim);
  const double box_speed = sim.qdot()[sim.model().bodies[1].dof];
  std::printf("momentum before (%.6f, %.6f, %.6f), after (%.6f, %.6f, %.6f) kg·m/s; %d steps in contact; box at %.3f m/s\n",
              p0.x(), p0.y(), p0.z(), p1.x(), p1.y(), p1.z(), steps_in_contact, box_speed);
  EXPECT_GT(steps_in_contact, 3) << "the bodies must have collided";
  EXPECT_GT(box_speed, 0.3) << "the box must have been pushed";
  EXPECT_LT((p1 - p0).norm(), 1e-3 * p0.norm());
}

TEST(Hybrid, SquashedStableNeoHookeanCubeRecoversItsRestShape) {
  // A kinematic plate presses a soft cube to a quarter of its height, then rises away; the
  // cube ends unsquashed: no NaN, no inverted tet, every edge back to its rest length.
  Simulation sim = simulate(R"({"description": "squash and recover", "gravity": [0, 0, 0],
    "time": {"dt": 0.01},
    "bodies": [
      {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [0.6, 0.05, 0.6]}, "position": [0, -0.025, 0]},
      {"name": "cube", "model": "soft", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [0, 0.102, 0],
       "mesh_size": 0.07, "material": {"model": "stable_neo_hookean", "young": 1e5, "poisson": 0.4}},
      {"name": "press", "kind": "kinematic", "mesh": {"primitive": "box", "size": [0.6, 0.05, 0.6]}, "position": [0, 0.229, 0],
       "path": [{"duration": 0.5, "velocity": [0, -0.3, 0]}], "velocity": [0, 1, 0]}]})");
  const Model& model = sim.model();
  double max_energy = 0;
  for (int k = 0; k < 150; ++k) {
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged) << "step " << s.step << ": " << s.newton.failure;
    ASSERT_TRUE(sim.q().allFinite());
    max_energy = std::max(max_energy, s.elastic_energy);
  }
  const Eigen::MatrixX3d x = sim.node_positions();
  double worst = 0;
  for (int t = 0; t < model.nodes.T.rows(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const int i = model.nodes.T(t, a), j = model.nodes.T(t, b);
        const double rest = (model.nodes.X.row(i) - model.nodes.X.row(j)).norm();
        worst = std::max(worst, std::abs((x.row(i) - x.row(j)).norm() - rest) / rest);
      }
  const StepStats last = sim.step();
  std::printf("largest elastic energy while squashed %.3g J; at the end %.3g J, worst edge strain %.2e, %d inverted\n",
              max_energy, last.elastic_energy, worst, last.inverted_tets);
  EXPECT_GT(max_energy, 10.0) << "the cube must have been squashed hard";
  EXPECT_EQ(last.inverted_tets, 0);
  EXPECT_LT(worst, 0.02);
}

TEST(Hybrid, AutoModelMakesStiffBodiesAffineAndSoftBodiesSoft) {
  Simulation sim = simulate(R"({"description": "auto",
    "bodies": [
      {"name": "ground", "kind": "fixed", "mesh": {"primitive": "plane", "size": [2, 0.05, 2]}, "position": [0, -0.025, 0]},
      {"name": "steel", "model": "auto", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [-0.3, 0.3, 0],
       "density": 7800, "material": {"young": 2e11, "poisson": 0.3}},
      {"name": "rubber", "model": "auto", "mesh": {"primitive": "sphere", "radius": 0.1}, "position": [0.3, 0.3, 0],
       "density": 1100, "material": {"young": 1e6, "poisson": 0.45}}]})");
  EXPECT_EQ(sim.model().bodies[1].representation, Representation::Affine);
  EXPECT_EQ(sim.model().bodies[2].representation, Representation::Soft);
}

TEST(Hybrid, KinematicBodyFollowsItsPathLegsThenItsVelocity) {
  Simulation sim = simulate(R"({"description": "path", "gravity": [0, 0, 0], "time": {"dt": 0.01},
    "bodies": [{"name": "plate", "kind": "kinematic", "mesh": {"primitive": "box", "size": [0.2, 0.05, 0.2]},
      "path": [{"duration": 0.1, "velocity": [0, -1, 0]}, {"duration": 0.1, "angular_velocity": [0, 0, 1]}],
      "velocity": [1, 0, 0]}]})");
  for (int k = 0; k < 30; ++k) ASSERT_TRUE(sim.step().newton.converged);
  const abd::Vector12d q = sim.q().segment<12>(0);
  // Legs: 0.1 m down, then a turn of 0.1 rad about z, then 0.1 m along x.
  EXPECT_NEAR(q[0], 0.1, 1e-4);
  EXPECT_NEAR(q[1], -0.1, 1e-4);
  const Eigen::Matrix3d A = abd::affine_matrix(q);
  EXPECT_NEAR(A(1, 0), std::sin(0.1), 1e-4);
  EXPECT_NEAR(A(0, 0), std::cos(0.1), 1e-4);
}

namespace {

/// Runs a broken scene of tests/apps/data; expects exit code 2 and every needle in the log.
void expect_soft_scene_error(const std::string& file, const std::vector<std::string>& needles) {
  const fs::path out = temporary_folder("stiffsoft_broken_soft");
  const fs::path scene = fs::path(STIFFSOFT_SOURCE_DIR) / "tests/apps/data" / file;
  EXPECT_EQ(run_stiffsoft("run " + scene.string() + " -o " + (out / "o").string(), out / "run.log"), 2);
  const std::string log = read_text(out / "run.log");
  for (const std::string& n : needles) EXPECT_NE(log.find(n), std::string::npos) << "missing '" << n << "' in:\n" << log;
  EXPECT_FALSE(fs::exists(out / "o" / "stats.csv"));
  fs::remove_all(out);
}

}  // namespace

TEST(BrokenSoftScene, DirichletSelectingNothingNamesTheCondition) {
  expect_soft_scene_error("soft_dirichlet_selects_nothing.json",
                          {"soft_dirichlet_selects_nothing.json", "bodies[0].dirichlet[1]", "selects no node", "jelly"});
}

TEST(BrokenSoftScene, UnknownNodeSetListsTheMeshsSets) {
  expect_soft_scene_error("soft_unknown_node_set.json", {"bodies[0].dirichlet[0]", "no node set named 'base'"});
}

TEST(BrokenSoftScene, GarbageMeshFileNamesTheFile) {
  expect_soft_scene_error("soft_garbage_msh.json", {"soft_garbage_msh.json", "bodies[0].mesh", "garbage.msh"});
}

TEST(BrokenSoftScene, OpenSurfaceIsRefusedBeforeMeshing) {
  expect_soft_scene_error("soft_open_surface.json", {"bodies[0].mesh", "closed"});
}

TEST(BrokenSoftScene, SelfIntersectingSurfaceIsRefused) {
  expect_soft_scene_error("soft_self_intersecting.json", {"bodies[0].mesh", "self-intersecting"});
}
