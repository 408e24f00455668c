#pragma once
/// @file Running the scenes of a study: independent child processes of the `stiffsoft`
/// binary (`run`, then `check`), several at a time, each result cached in its folder.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <stiffsoft/study/sweep.hpp>

namespace stiffsoft::study {

/// What one run did.
struct RunResult {
  std::filesystem::path dir;  ///< DIR/runs/<hash>: scene.json, run.log, stats.csv, bodies.csv, frames
  int exit_code = -1;         ///< of `stiffsoft run`: 0 converged, 3 some step did not, other: failed
  int check_code = -1;        ///< of `stiffsoft check`: 0 every frame intersection-free, 1 not; −1 not checked
  double wall_seconds = 0;    ///< wall time of `stiffsoft run` (s), process start to exit
  bool cached = false;        ///< taken from an earlier study run (result.json already there)
};

/// How runs are started.
struct RunnerOptions {
  std::filesystem::path binary;  ///< the stiffsoft executable
  std::filesystem::path runs;    ///< DIR/runs
  int jobs = 1;                  ///< runs at a time, ≥ 1
  int threads = 1;               ///< --threads of each run
  bool check = true;             ///< also run `stiffsoft check` on each run's frames
};

/// Runs every distinct scene of `runs` (by hash) that has no result.json yet, `jobs` at a time,
/// and returns the results by hash. A run's folder gets scene.json (the resolved scene), its
/// outputs, run.log / check.log and, when both processes have ended, result.json (written
/// last and atomically, so an interrupted study re-runs exactly the unfinished runs).
/// Children get the parent's environment without MPI launcher variables (OMPI_*, PMIX_*), so
/// each starts as its own MPI singleton. Throws std::runtime_error when a process cannot be started.
std::map<std::string, RunResult> run_all(const std::vector<const RunPlan*>& runs, const RunnerOptions& options);

/// Runs `args` (args[0]: the program, searched in PATH when it has no '/') to completion with
/// stdout and stderr going to `log`, in the same cleaned environment as the runs. Returns its
/// exit code (127 when it cannot be started).
int run_process(const std::vector<std::string>& args, const std::filesystem::path& log);

}  // namespace stiffsoft::study
