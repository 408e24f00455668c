/// @file Every shipped scene runs through the `stiffsoft` binary (a few steps), its frames pass
/// `stiffsoft check`, and every step's Newton converged; broken input gives a clear error.

#include <gtest/gtest.h>

#include "io/frame_writer.hpp"
#include "meshing/primitive.hpp"
#include "scene_helpers.hpp"

using namespace stiffsoft::testing;
namespace fs = std::filesystem;

namespace {

struct SceneCase {
  std::string name;
  int steps;
};

class ShippedScene : public ::testing::TestWithParam<SceneCase> {};

}  // namespace

TEST_P(ShippedScene, RunsConvergesAndStaysIntersectionFree) {
  const SceneCase& c = GetParam();
  const fs::path out = fresh_folder("stiffsoft_scene_" + c.name);
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

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene,
                         ::testing::Values(SceneCase{"default", 60}, SceneCase{"box_stack", 60},
                                           SceneCase{"house_of_cards", 40}, SceneCase{"incline_stick", 40},
                                           SceneCase{"incline_slide", 40}, SceneCase{"wrecking_ball", 40},
                                           SceneCase{"thin_wall", 20}, SceneCase{"light", 40},
                                           SceneCase{"medium", 10}, SceneCase{"full", 3},
                                           SceneCase{"soft_ball_on_boxes", 60}, SceneCase{"cube_on_mattress", 40},
                                           SceneCase{"beam_with_blocks", 30}, SceneCase{"mixed_pile", 20},
                                           SceneCase{"squash_recover", 20}, SceneCase{"pendulum", 40},
                                           SceneCase{"double_pendulum", 40}, SceneCase{"chain", 40},
                                           SceneCase{"top_slow", 40}, SceneCase{"top_medium", 40}, SceneCase{"top_fast", 40},
                                           SceneCase{"door_and_ball", 40}, SceneCase{"hanging_bridge", 30},
                                           SceneCase{"umbrella", 40}, SceneCase{"ragdoll_steps", 30},
                                           SceneCase{"slider_spring_rope", 60}, SceneCase{"cone_twist_chain", 40},
                                           SceneCase{"glued_block", 30}),
                         [](const auto& info) { return info.param.name; });

namespace {

/// Runs a broken scene; expects exit code 2 and every `needles` in the log.
void expect_scene_error(const std::string& file, const std::vector<std::string>& needles) {
  const fs::path out = fresh_folder("stiffsoft_broken");
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
  expect_scene_error("../../io/data/broken/negative_density.json", {"negative_density.json", "density"});
  expect_scene_error("../../io/data/broken/missing_mesh_file.json", {"missing_mesh_file.json", "mesh"});
}

TEST(Check, FindsTheIntersectingFrameAndNamesTheBodies) {
  const fs::path out = fresh_folder("stiffsoft_check");
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
  const fs::path out = fresh_folder("stiffsoft_check_missing");
  EXPECT_EQ(run_stiffsoft("check " + (out / "missing.pvd").string(), out / "check.log"), 1);
  EXPECT_NE(read_text(out / "check.log").find("missing.pvd"), std::string::npos);
  fs::remove_all(out);
}
