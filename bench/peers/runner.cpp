#include "peers/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "peers/machine.hpp"

#include "bench_statistics.hpp"

namespace stiffsoft::peers {

namespace {

using stiffsoft::bench::median;

double mean(const std::vector<double>& v) {
  return v.empty() ? 0 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

}  // namespace

RunResult run_engine(const std::string& name, const PeerScene& scene, double duration, const RunOptions& options) {
  RunResult r;
  r.engine = name;
  r.scene = scene.name;
  r.bodies = int(scene.bodies.size());
  r.dynamic_bodies = scene.dynamic_bodies();
  r.triangles = scene.triangles;
  r.dt = scene.dt;
  const int planned = std::max(1, int(std::lround(duration / scene.dt)));
  r.threads = name.rfind("stiffsoft", 0) == 0 ? options.threads : 1;
  r.load_before = load_average();

  std::unique_ptr<Engine> engine = make_engine(name, scene, options.engines);
  r.settings = engine->settings();
  AccuracyMonitor monitor(scene);
  const int check_every = std::max(1, int(std::lround(1.0 / (options.check_fps * scene.dt))));
  std::vector<double> ms, iterations;
  std::vector<double> broad, ccd, assembly, solve;
  double wall_ms = 0;
  for (int k = 1; k <= planned; ++k) {
    const auto start = std::chrono::steady_clock::now();
    engine->step();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    wall_ms += ms.back();
    const bool last = k == planned || (options.max_wall_s > 0 && wall_ms > 1e3 * options.max_wall_s);
    const double t = k * scene.dt;
    const StepDetails d = engine->details();
    if (d.newton_iterations >= 0) {
      iterations.push_back(d.newton_iterations);
      r.unconverged += d.converged ? 0 : 1;
      broad.push_back(1e3 * d.broad_phase_s);
      ccd.push_back(1e3 * d.ccd_s);
      assembly.push_back(1e3 * d.assembly_s);
      solve.push_back(1e3 * d.solve_s);
      monitor.distance(d.smallest_distance);
    }
    monitor.contacts(engine->penetrations(), t);
    if (k % check_every == 0 || last) {
      if (last) {
        engine->finish_probe();
        monitor.contacts(engine->penetrations(), t);
      }
      monitor.frame(*engine, t);
    }
    if (last) break;
  }
  r.steps = int(ms.size());
  r.duration = r.steps * scene.dt;
  r.ms_median = median(ms);
  r.ms_mean = mean(ms);
  r.wall_s = std::accumulate(ms.begin(), ms.end(), 0.0) / 1e3;
  if (!iterations.empty()) {
    r.newton_mean = mean(iterations);
    r.broad_phase_ms = mean(broad);
    r.ccd_ms = mean(ccd);
    r.assembly_ms = mean(assembly);
    r.solve_ms = mean(solve);
  }
  r.accuracy = monitor.report();
  r.warnings = engine->warnings();
  if (r.steps < planned) {
    char text[160];
    std::snprintf(text, sizeof text, "stopped unfinished after %.0f s of stepping (--max-wall): %d of %d steps",
                  wall_ms / 1e3, r.steps, planned);
    r.warnings = r.warnings.empty() ? text : r.warnings + "; " + text;
  }
  r.statistics = engine->statistics();
  r.load_after = load_average();
  return r;
}

}  // namespace stiffsoft::peers
