#pragma once
/// @file One engine, one scene, one time step: timed steps plus the accuracy checks.

#include <string>

#include "peers/accuracy.hpp"
#include "peers/engines.hpp"
#include "peers/peer_scene.hpp"

namespace stiffsoft::peers {

/// How runs are made.
struct RunOptions {
  EngineOptions engines;    ///< engine settings
  double check_fps = 60;    ///< frames per simulated second checked for intersections and tunnelling
  int threads = 0;          ///< stiffsoft's worker threads (recorded; set by the caller); peers run on one
  double max_wall_s = 0;    ///< a run stops after this much stepping wall time (s), unfinished; 0: no limit
};

/// The result of one run: a row of the CSV.
struct RunResult {
  std::string engine;         ///< engine name
  std::string scene;          ///< scene name
  int bodies = 0;             ///< all bodies
  int dynamic_bodies = 0;     ///< non-fixed bodies
  int triangles = 0;          ///< triangles of all bodies
  double dt = 0;              ///< time step h (s)
  int steps = 0;              ///< steps run (fewer than round(duration / h) when stopped by max_wall_s)
  double duration = 0;        ///< simulated time (s)
  double ms_median = 0;       ///< median wall time per step (ms)
  double ms_mean = 0;         ///< mean wall time per step (ms)
  double wall_s = 0;          ///< wall time of all steps (s), checks excluded
  double newton_mean = -1;    ///< stiffsoft: mean Newton iterations per step; −1 for peers
  int unconverged = 0;        ///< stiffsoft: steps that hit the iteration cap
  double broad_phase_ms = 0;  ///< stiffsoft: mean broad-phase time per step (ms)
  double ccd_ms = 0;          ///< stiffsoft: mean CCD time per step (ms)
  double assembly_ms = 0;     ///< stiffsoft: mean assembly time per step (ms)
  double solve_ms = 0;        ///< stiffsoft: mean linear-solve time per step (ms)
  AccuracyReport accuracy;    ///< what the checks found
  std::string warnings;       ///< the engine's own warnings
  std::string statistics;     ///< the engine's counters (MuJoCo's peak buffer use)
  std::string settings;       ///< the engine's settings line
  int threads = 1;            ///< threads the engine ran on
  double load_before = -1;    ///< 1-minute load average before the run
  double load_after = -1;     ///< and after
};

/// Runs `engine` on `scene` for round(duration / h) steps, timing each step() alone; with
/// options.max_wall_s, stops after the step that exceeds it and says so in the warnings.
RunResult run_engine(const std::string& engine, const PeerScene& scene, double duration, const RunOptions& options);

}  // namespace stiffsoft::peers
