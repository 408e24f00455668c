/// @file The front door: <stiffsoft/stiffsoft.hpp> alone turns a scene file or a scene built in
/// code into a ready Simulation, with the same checks and errors as `stiffsoft run`, and the
/// Recorder writes what `stiffsoft run` writes.

#include <stiffsoft/stiffsoft.hpp>

#include <gtest/gtest.h>

#include <fstream>

#include "scene_helpers.hpp"

using namespace stiffsoft;
namespace fs = std::filesystem;

namespace {

/// A box dropping onto a fixed slab, built in code.
SceneDescription box_on_slab() {
  SceneDescription scene;
  scene.name = "box_on_slab";
  scene.description = "a box dropping onto a slab";
  scene.time.duration = 0.1;
  BodyDescription slab;
  slab.name = "slab";
  slab.kind = Motion::Fixed;
  slab.mesh.primitive = PrimitiveShape{};
  slab.mesh.primitive->extents = {2, 0.1, 2};
  BodyDescription box;
  box.name = "box";
  box.mesh.primitive = PrimitiveShape{};
  box.mesh.primitive->extents = {0.2, 0.2, 0.2};
  box.position = {0, 0.2, 0};
  scene.bodies = {slab, box};
  return scene;
}

}  // namespace

TEST(FrontDoor, ASceneFileBecomesTheSimulationStiffsoftRunSteps) {
  const fs::path file = fs::path(STIFFSOFT_SOURCE_DIR) / "scenes" / "box_stack.json";
  SceneSimulation run = make_simulation(file);
  const SceneDescription loaded = load_scene(file);
  EXPECT_EQ(run.scene.name, "box_stack");
  // Relative defaults are resolved: d̂ = 1e-3 L (below 1 % of the smallest body here), ε_d = 1e-2 L/s, frame_dt = max(dt, 1/60).
  const double L = run.simulation.model().bounding_box_diagonal();
  EXPECT_DOUBLE_EQ(*run.scene.contact.dhat, 1e-3 * L);
  EXPECT_DOUBLE_EQ(run.simulation.settings().dhat, 1e-3 * L);
  EXPECT_DOUBLE_EQ(run.simulation.settings().tolerance, 1e-2 * L);
  EXPECT_DOUBLE_EQ(*run.scene.output.frame_dt, std::max(loaded.time.dt, 1.0 / 60.0));
  EXPECT_TRUE(run.simulation.step().newton.converged);
}

TEST(FrontDoor, ASceneBuiltInCodeRunsLikeTheSameSceneFromJson) {
  const SceneDescription scene = box_on_slab();
  SceneSimulation in_code = make_simulation(scene);
  SceneSimulation from_json = make_simulation(
      load_scene_from_string(resolved_scene_json(scene).dump(), STIFFSOFT_SOURCE_DIR, "box.json", scene.name));
  for (int k = 0; k < 5; ++k) {
    in_code.simulation.step();
    from_json.simulation.step();
  }
  EXPECT_EQ((in_code.simulation.q() - from_json.simulation.q()).cwiseAbs().maxCoeff(), 0.0);
}

TEST(FrontDoor, ASceneBuiltInCodeGetsTheSchemasErrorsWithItsJsonPath) {
  SceneDescription scene = box_on_slab();
  scene.bodies[1].density = -2;
  try {
    make_simulation(scene);
    FAIL() << "a negative density was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), "box_on_slab (built in code)");
    EXPECT_EQ(e.json_path(), "bodies[1].density");
  }
  scene = box_on_slab();
  scene.bodies[1].name = "slab";
  EXPECT_THROW(make_simulation(scene, "my scene"), SceneError);
}

TEST(FrontDoor, SettingsBuiltInCodeAreValidatedWithTheSettingsName) {
  PreparedScene prepared = prepare_scene(box_on_slab());
  const auto message = [&](const std::function<void(SimulationSettings&)>& change) {
    SimulationSettings s = prepared.settings;
    change(s);
    try {
      validate(s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message([](SimulationSettings&) {}), "accepted");
  EXPECT_EQ(message([](SimulationSettings& s) { s.dhat = -1; }), "SimulationSettings.dhat: must be > 0 and finite (got -1)");
  EXPECT_EQ(message([](SimulationSettings& s) { s.h = 0; }), "SimulationSettings.h: must be > 0 and finite (got 0)");
  EXPECT_EQ(message([](SimulationSettings& s) { s.max_iterations = 0; }), "SimulationSettings.max_iterations: must be ≥ 1 (got 0)");
  EXPECT_EQ(message([](SimulationSettings& s) { s.release_hessian = 0; }),
            "SimulationSettings.release_hessian: must be in (0, 1] (got 0)");
  EXPECT_EQ(message([](SimulationSettings& s) { s.gap_tolerance = 0; }),
            "SimulationSettings.gap_tolerance: must be > 0 and finite (got 0)");
  EXPECT_EQ(message([](SimulationSettings& s) { s.friction_iterations = 0; }),
            "SimulationSettings.friction_iterations: must be ≥ 1 (got 0)");
  EXPECT_EQ(message([](SimulationSettings& s) { s.krylov_rtol_max = 1; }), "SimulationSettings.krylov_rtol_max: must be in (0, 1) (got 1)");
  EXPECT_NE(message([](SimulationSettings& s) { s.linear_solver = "gauss"; }).find("SimulationSettings.linear_solver: "),
            std::string::npos);
  prepared.settings.eps_v = 0;
  EXPECT_THROW(Simulation(std::move(prepared.model), prepared.settings), std::invalid_argument);
}

TEST(FrontDoor, TheRecorderWritesWhatStiffsoftRunWrites) {
  const fs::path out = stiffsoft::testing::temporary_folder("stiffsoft_recorder");
  SceneSimulation run = make_simulation(box_on_slab());
  {
    Recorder recorder(out, run.scene, run.simulation);
    for (int k = 1; k <= 6; ++k) recorder.record(run.simulation.step(), k == 6);
    recorder.finish();
    // t = 0, then every frame_dt = max(h, 1/60 s) (after steps 2, 4, 5) and the last step.
    EXPECT_EQ(recorder.frame_count(), 5);
  }
  for (const char* name : {"box_on_slab.pvd", "stats.csv", "bodies.csv", "scene.resolved.json"})
    EXPECT_TRUE(fs::exists(out / name)) << name;
  EXPECT_EQ(stiffsoft::testing::csv_column(out / "stats.csv", "newton_iterations").size(), 6u);
  const std::vector<std::string> names = step_stats_column_names();
  EXPECT_EQ(stiffsoft::testing::read_text(out / "stats.csv").substr(0, names[0].size() + names[1].size() + 1), "step,time");
  EXPECT_EQ(load_scene(out / "scene.resolved.json").bodies.size(), 2u);
  fs::remove_all(out);
}

TEST(FrontDoor, TheRecorderReportsAWriteThatFailedAtItsNextCallAndKeepsWhatItWrote) {
  const fs::path out = stiffsoft::testing::temporary_folder("stiffsoft_recorder_failure");
  SceneSimulation run = make_simulation(box_on_slab());
  {
    Recorder recorder(out, run.scene, run.simulation);
    for (int k = 1; k <= 2; ++k) recorder.record(run.simulation.step());  // frames: t = 0, after step 2
    recorder.finish();
    ASSERT_EQ(recorder.frame_count(), 2);
    fs::remove_all(out / "frames");
    std::ofstream(out / "frames") << "a file where the frames' folder was";
    // The frame after step 4 cannot be written; the writer's thread learns it, the caller at its
    // next call (record() or finish()).
    bool thrown = false;
    try {
      for (int k = 3; k <= 6; ++k) recorder.record(run.simulation.step());
      recorder.finish();
    } catch (const std::runtime_error& e) {
      thrown = true;
      EXPECT_NE(std::string(e.what()).find((out / "frames").string()), std::string::npos) << e.what();
    }
    EXPECT_TRUE(thrown);
    EXPECT_EQ(recorder.frame_count(), 2);
    EXPECT_THROW(recorder.finish(), std::runtime_error);  // the output stays stopped
    // The .pvd and the checkpoint still list the two frames written, and stats.csv holds the
    // rows through the last of them.
    EXPECT_EQ(read_checkpoint(out / "checkpoint.bin").frames.size(), 2u);
    EXPECT_EQ(read_checkpoint(out / "checkpoint.bin").state.step, 2);
    EXPECT_EQ(stiffsoft::testing::csv_column(out / "stats.csv", "newton_iterations").size(), 2u);
    const std::string pvd = stiffsoft::testing::read_text(out / "box_on_slab.pvd");
    EXPECT_NE(pvd.find("box_on_slab_000001.vtm"), std::string::npos);
    EXPECT_EQ(pvd.find("box_on_slab_000002.vtm"), std::string::npos);
  }
  // Nothing recorded before the failure is lost: the recorder's end writes the rows of steps 3
  // and 4, queued before the failed frame (what was queued after it was dropped).
  EXPECT_EQ(stiffsoft::testing::csv_column(out / "stats.csv", "newton_iterations").size(), 4u);
  fs::remove_all(out);
}

TEST(FrontDoor, TheRecorderRefusesAnOutputFolderThatIsAFile) {
  const fs::path dir = stiffsoft::testing::temporary_folder("stiffsoft_recorder_file");
  const fs::path file = dir / "taken";
  std::ofstream(file) << "not a folder";
  SceneSimulation run = make_simulation(box_on_slab());
  try {
    Recorder recorder(file, run.scene, run.simulation);
    FAIL() << "a file was taken for the output folder";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "output folder " + file.string() + ": exists and is not a folder");
  }
  EXPECT_EQ(stiffsoft::testing::read_text(file), "not a folder");  // nothing already written is lost
  fs::remove_all(dir);
}
