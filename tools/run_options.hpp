#pragma once
/// @file What the diagnostics in tools/ share: their options for the run to look at, and
/// continuing that run from its checkpoint.

#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>

#include <stiffsoft/io/checkpoint.hpp>
#include <stiffsoft/scene/make_simulation.hpp>

namespace stiffsoft::tools {

/// The scene, the run of it to continue (empty: start the scene), the steps and the threads.
struct RunOptions {
  std::string scene_file;  ///< scene file (JSON)
  std::string run_dir;     ///< output folder of a run of that scene, or empty
  int steps = 10;          ///< steps to take
  int threads = 1;         ///< worker threads

  /// Declares them on `app`; `what` says what the steps are taken for ("probe", "trace").
  void add_to(CLI::App& app, const std::string& what) {
    app.add_option("scene", scene_file, "scene file (JSON)")->required()->check(CLI::ExistingFile);
    app.add_option("--resume", run_dir, "output folder of a run of that scene: start from its checkpoint.bin");
    app.add_option("--steps", steps, "steps to take and " + what)->check(CLI::PositiveNumber);
    app.add_option("--threads", threads, "threads")->check(CLI::PositiveNumber);
  }
};

/// Puts `run` (made from options.scene_file) at the state of options.run_dir's checkpoint.bin
/// when run_dir is given; ResumeError when that checkpoint was written for another version of
/// the scene.
inline void resume_run(SceneSimulation& run, const RunOptions& options) {
  if (options.run_dir.empty()) return;
  const Checkpoint checkpoint = read_checkpoint(std::filesystem::path(options.run_dir) / "checkpoint.bin");
  if (checkpoint.scene_fingerprint != scene_fingerprint(run.scene))
    throw ResumeError(options.run_dir + "/checkpoint.bin: written for another version of " + options.scene_file);
  run.simulation.restore(checkpoint.state);
}

}  // namespace stiffsoft::tools
