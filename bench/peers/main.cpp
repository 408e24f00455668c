/// @file peer_bench: stiffsoft side by side with Bullet (convex hulls and triangle meshes) and
/// MuJoCo on the same scene files (docs/peers.md). For each scene, time step and engine: median
/// ms per step, Newton iterations (stiffsoft), and the accuracy checks of peers/accuracy.hpp.
/// Writes a CSV (bench/peers/report_peers.py turns it into the Markdown table and the plot).
/// `peer_bench --help` lists the options; `peer_bench --verify` checks the scene mapping.

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include "peers/csv.hpp"
#include "peers/machine.hpp"
#include "peers/runner.hpp"
#include "peers/verify.hpp"

using namespace stiffsoft::peers;

namespace {

/// "1/240" or "0.0041666" → seconds.
double parse_time_step(const std::string& text) {
  const size_t slash = text.find('/');
  const double value = slash == std::string::npos ? std::stod(text)
                                                  : std::stod(text.substr(0, slash)) / std::stod(text.substr(slash + 1));
  if (!(value > 0)) throw std::invalid_argument("--dt: time steps must be > 0 (got '" + text + "')");
  return value;
}

std::string millimetres(double metres) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g mm", 1e3 * metres);
  return buffer;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"stiffsoft vs Bullet vs MuJoCo on stiffsoft scene files (docs/peers.md)"};
  std::vector<std::string> scenes{"light", "medium", "full", "house_of_cards", "wrecking_ball", "chain_net"};
  std::vector<std::string> dts{"1/100", "1/240", "1/1000"};
  std::vector<std::string> engines = available_engines();
  double duration = 2.0;
  int threads = 0;
  bool verify = false;
  RunOptions options;
  std::filesystem::path scene_dir = STIFFSOFT_SOURCE_DIR "/scenes", csv = "peers.csv";
  app.add_option("--scenes", scenes, "scene names in the scene folder")->delimiter(',');
  app.add_option("--dt", dts, "time steps (s), e.g. 1/240 or 0.01")->delimiter(',');
  app.add_option("--engines", engines,
                 "engines to run (default: all in this build: " + available_engine_list() + ")")
      ->delimiter(',');
  app.add_option("--duration", duration, "simulated time of every run (s); steps = round(duration / h)");
  app.add_option("--threads", threads, "stiffsoft worker threads (0: all cores); Bullet and MuJoCo use one");
  app.add_option("--scene-dir", scene_dir, "folder of the scenes");
  app.add_option("--csv", csv, "CSV output (appended rows are flushed after each run)");
  app.add_option("--max-wall", options.max_wall_s,
                 "stop a run after this much stepping wall time (s) and report it unfinished; 0: no limit");
  app.add_option("--check-fps", options.check_fps, "frames per simulated second checked for intersections");
  app.add_option("--bullet-margin", options.engines.bullet_margin,
                 "Bullet (bullet, bullet_mesh) margin of hull and mesh shapes (m); 0: half the scene's d^");
  app.add_option("--mujoco-nconmax", options.engines.mujoco_nconmax, "MuJoCo contact buffer (0: automatic)");
  app.add_option("--mujoco-njmax", options.engines.mujoco_njmax, "MuJoCo constraint rows (0: automatic)");
  app.add_option("--sleep-time", options.engines.sleep_time,
                 "stiffsoft-sleep: seconds at rest before a body sleeps (solver.sleep_time)");
  app.add_flag("--verify", verify, "check that each engine holds the same scene as stiffsoft, then exit");
  CLI11_PARSE(app, argc, argv);

  const Machine machine = this_machine();
  const int used_threads = threads > 0 ? threads : int(machine.cores);
  tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(used_threads));
  options.threads = used_threads;
  try {
    if (verify) {
      std::vector<std::filesystem::path> files;
      for (const std::string& name : scenes) files.push_back(scene_dir / (name + ".json"));
      const int failures = verify_engines(engines, files, options.engines);
      std::printf("%d check(s) failed\n", failures);
      return failures ? 1 : 0;
    }
    std::ofstream out(csv);
    if (!out) throw std::runtime_error("cannot write " + csv.string());
    write_csv_header(out, machine, used_threads);
    std::printf("# %u cores, %s, %s; stiffsoft on %d threads, peers on 1\n", machine.cores, machine.cpu.c_str(),
                machine.date.c_str(), used_threads);
    for (const std::string& name : scenes)
      for (const std::string& dt_text : dts) {
        const double dt = parse_time_step(dt_text);
        const PeerScene scene = load_peer_scene(scene_dir / (name + ".json"), dt);
        for (const std::string& engine : engines) {
          const RunResult r = run_engine(engine, scene, duration, options);
          write_csv_row(out, r);
          const AccuracyReport& a = r.accuracy;
          std::printf("%-17s %-14s h = %-6s %5d steps  %9.3f ms/step", r.engine.c_str(), r.scene.c_str(),
                      dt_text.c_str(), r.steps, r.ms_median);
          if (r.newton_mean >= 0) std::printf("  %.2f it.", r.newton_mean);
          std::printf("  intersecting frames %d/%d  overlap %s  engine depth %s  %s%s\n", a.frames_intersecting,
                      a.frames_checked, millimetres(a.max_overlap).c_str(), millimetres(a.max_engine_depth).c_str(),
                      a.tunnelled ? "TUNNELLED: " : "no tunnelling", a.tunnel_note.c_str());
          if (!r.warnings.empty()) std::printf("          warnings: %s\n", r.warnings.c_str());
          if (!r.statistics.empty()) std::printf("          %s\n", r.statistics.c_str());
          std::fflush(stdout);
        }
      }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "peer_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
