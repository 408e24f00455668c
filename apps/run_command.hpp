#pragma once
/// @file `stiffsoft run SCENE.json -o DIR`.

#include <filesystem>
#include <optional>

#include <stiffsoft/io/recorder.hpp>
#include <stiffsoft/scene/element_limits.hpp>

namespace stiffsoft {

/// Options of `stiffsoft run`.
struct RunOptions {
  std::filesystem::path scene;   ///< scene file
  std::filesystem::path out;     ///< output folder
  std::optional<int> steps;      ///< run this many steps instead of the scene's duration
  int threads = 0;               ///< worker threads; 0: all cores
  ElementLimits limits;          ///< largest body the scene may build (--max-tets, --max-triangles)
  double load_timeout = 900;     ///< bound on loading and meshing (s, --load-timeout); ≤ 0: none
  bool resume = false;           ///< continue the run in `out` from its checkpoint (--resume)
  int checkpoint_every = Recorder::kCheckpointEvery;  ///< frames between checkpoints (--checkpoint-every); 0: none
};

/// Runs a scene, writing frames, stats.csv, bodies.csv and scene.resolved.json into the output
/// folder (under MPI: rank 0 only). Returns the process exit code (0: every step's Newton converged; 3: some did not, or a
/// PhysicsError stopped the run, every file written so far kept).
int run_scene(const RunOptions& options);

}  // namespace stiffsoft
