#pragma once
/// @file What the diagnostics in tools/ share: continuing a run from its checkpoint.

#include <filesystem>
#include <string>

#include <stiffsoft/io/checkpoint.hpp>
#include <stiffsoft/scene/make_simulation.hpp>

namespace stiffsoft::tools {

/// Puts `run` (made from `scene_file`) at the state of `run_dir`/checkpoint.bin; ResumeError
/// when that checkpoint was written for another version of the scene.
inline void resume_run(SceneSimulation& run, const std::string& scene_file, const std::string& run_dir) {
  const Checkpoint checkpoint = read_checkpoint(std::filesystem::path(run_dir) / "checkpoint.bin");
  if (checkpoint.scene_fingerprint != scene_fingerprint(run.scene))
    throw ResumeError(run_dir + "/checkpoint.bin: written for another version of " + scene_file);
  run.simulation.restore(checkpoint.state);
}

}  // namespace stiffsoft::tools
