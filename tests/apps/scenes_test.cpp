/// @file Every shipped scene runs through the `stiffsoft` binary (a few steps), its frames pass
/// `stiffsoft check`, and every step's Newton converged; broken input gives a clear error.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include <stiffsoft/io/frame_writer.hpp>
#include <stiffsoft/meshing/primitive.hpp>
#include "scene_helpers.hpp"

using namespace stiffsoft::testing;
namespace fs = std::filesystem;

namespace {

struct SceneCase {
  std::string name;  ///< scenes/<name>.json
  int steps;         ///< steps to run
};

/// How gtest shows a case (in --gtest_list_tests and failures).
void PrintTo(const SceneCase& c, std::ostream* os) { *os << c.name << ", " << c.steps << " steps"; }

class ShippedScene : public ::testing::TestWithParam<SceneCase> {};

}  // namespace

TEST_P(ShippedScene, RunsConvergesAndStaysIntersectionFree) {
  const SceneCase& c = GetParam();
  const fs::path out = temporary_folder("stiffsoft_scene_" + c.name);
  const fs::path scene = fs::path(STIFFSOFT_SOURCE_DIR) / "scenes" / (c.name + ".json");
  ASSERT_EQ(run_stiffsoft("run " + scene.string() + " -o " + out.string() + " --steps " + std::to_string(c.steps),
                          out / "run.log"),
            0)
      << read_text(out / "run.log");
  const std::vector<double> converged = csv_column(out / "stats.csv", "converged");
  ASSERT_EQ(int(converged.size()), c.steps);
  for (size_t k = 0; k < converged.size(); ++k) EXPECT_EQ(converged[k], 1.0) << "step " << k + 1;
  EXPECT_TRUE(fs::exists(out / "scene.resolved.json"));
  EXPECT_EQ(run_stiffsoft("check " + (out / (c.name + ".pvd")).string(), out / "check.log"), 0)
      << read_text(out / "check.log");
  fs::remove_all(out);
}

namespace {

/// Steps of a scene the override map does not name: what most scenes need to get past their
/// first contacts and joint limits.
constexpr int kDefaultSteps = 40;

/// Scenes that run another number of steps than kDefaultSteps: the counts the former hand-kept
/// list gave them, and short runs of the expensive scenes. Each run (with its `stiffsoft
/// check`) stays well under ~20 s on a 2-core machine; the comments give the big scenes' test
/// times there (run + check).
const std::map<std::string, int> kStepOverrides{
    {"default", 60},
    {"ramp_and_boxes", 60},
    {"box_stack", 60},
    {"soft_ball_on_boxes", 60},
    {"slider_spring_rope", 60},
    {"beam_with_blocks", 30},
    {"hanging_bridge", 30},
    {"ragdoll_steps", 30},
    {"glued_block", 30},
    {"thin_wall", 20},
    {"mixed_pile", 20},
    {"squash_recover", 20},
    {"chain_net", 20},    // 64 rings, ~290 contacts by step 20: 6.5 s (40 steps: ~30 s)
    {"medium", 10},
    {"bricks_900", 8},    // 905 cubes, first contacts at step 5, 2557 at step 8: 5.2 s
    {"bricks_2400", 8},   // 2405 cubes, first contacts at step 5, 6954 at step 8: 10.7 s
    {"full", 3},
};

/// Every scenes/*.json, sorted by name, with its step count: a scene added to the folder is
/// tested without touching this file.
std::vector<SceneCase> shipped_scenes() {
  std::vector<SceneCase> cases;
  for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(STIFFSOFT_SOURCE_DIR) / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().stem().string();
    const auto override_steps = kStepOverrides.find(name);
    cases.push_back({name, override_steps == kStepOverrides.end() ? kDefaultSteps : override_steps->second});
  }
  std::sort(cases.begin(), cases.end(), [](const SceneCase& a, const SceneCase& b) { return a.name < b.name; });
  return cases;
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene, ::testing::ValuesIn(shipped_scenes()),
                         [](const auto& info) { return info.param.name; });

namespace {

/// Runs a broken scene; expects exit code 2 and every `needles` in the log.
void expect_scene_error(const std::string& file, const std::vector<std::string>& needles) {
  const fs::path out = temporary_folder("stiffsoft_broken");
  const fs::path scene = fs::path(STIFFSOFT_SOURCE_DIR) / "tests/apps/data" / file;
  EXPECT_EQ(run_stiffsoft("run " + scene.string() + " -o " + (out / "o").string(), out / "run.log"), 2);
  const std::string log = read_text(out / "run.log");
  for (const std::string& n : needles) EXPECT_NE(log.find(n), std::string::npos) << "missing '" << n << "' in:\n" << log;
  EXPECT_EQ(log.find("terminate"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out / "o" / "stats.csv")) << "a failed set-up must not start writing output";
  fs::remove_all(out);
}

}  // namespace

TEST(BrokenScene, NonClosedMeshNamesFileBodyAndProblem) {
  expect_scene_error("open_mesh.json", {"open_mesh.json", "bodies[0].mesh", "open_box", "closed"});
}

TEST(BrokenScene, OverlappingBodiesNameBothBodies) {
  expect_scene_error("overlapping_bodies.json", {"overlapping_bodies.json", "left_box", "right_box"});
}

TEST(BrokenScene, NestedBodiesAreAnOverlapToo) {
  expect_scene_error("nested_bodies.json", {"nested_bodies.json", "big_box", "small_box"});
}

TEST(BrokenScene, JsonErrorsExitWithTheLoadersMessage) {
  expect_scene_error("../../scene/data/broken/negative_density.json", {"negative_density.json", "density"});
  expect_scene_error("../../scene/data/broken/missing_mesh_file.json", {"missing_mesh_file.json", "mesh"});
}

TEST(Check, FindsTheIntersectingFrameAndNamesTheBodies) {
  const fs::path out = temporary_folder("stiffsoft_check");
  stiffsoft::PrimitiveShape cube;
  const stiffsoft::SurfaceMesh box = stiffsoft::make_primitive(cube);
  const auto frame = [&](double shift) {
    std::vector<stiffsoft::BodyFrame> bodies(2);
    bodies[0] = {"left_box", "affine", box.V, box.F, {}, {}, {}, {}};
    bodies[1] = {"right_box", "affine", box.V.rowwise() + Eigen::RowVector3d(shift, 0, 0), box.F, {}, {}, {}, {}};
    return bodies;
  };
  {
    stiffsoft::FrameWriter writer(out, "pair");
    writer.write(0.0, frame(1.5));  // apart
    writer.write(0.1, frame(0.7));  // overlapping
  }
  EXPECT_EQ(run_stiffsoft("check " + (out / "pair.pvd").string(), out / "check.log"), 1);
  const std::string log = read_text(out / "check.log");
  EXPECT_NE(log.find("pair_000001"), std::string::npos) << log;
  EXPECT_EQ(log.find("pair_000000"), std::string::npos) << log;
  EXPECT_NE(log.find("left_box"), std::string::npos) << log;
  EXPECT_NE(log.find("right_box"), std::string::npos) << log;
  fs::remove_all(out);
}

TEST(Check, MissingSeriesIsAClearError) {
  const fs::path out = temporary_folder("stiffsoft_check_missing");
  EXPECT_EQ(run_stiffsoft("check " + (out / "missing.pvd").string(), out / "check.log"), 1);
  EXPECT_NE(read_text(out / "check.log").find("missing.pvd"), std::string::npos);
  fs::remove_all(out);
}
