/// @file Time-step benchmark on the seed's Bullet-comparison piles: for each scene and time
/// step, median milliseconds per step, Newton iterations per step and seconds per phase.
/// `step_bench --help` lists the options; results go to stdout as a Markdown table and to CSV.

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <numeric>

#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene_loader.hpp>

#include "bench_statistics.hpp"

using namespace stiffsoft;

namespace {

using stiffsoft::bench::median;

double mean(const std::vector<double>& v) {
  return v.empty() ? 0 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

struct Row {
  std::string scene;
  int bodies, dofs, tets, triangles;
  double dt;
  int steps, unconverged;
  double ms_median, iterations, broad_phase_ms, ccd_ms, assembly_ms, solve_ms;
};

Row run(const std::filesystem::path& file, double dt, int steps) {
  SceneDescription scene = load_scene(file);
  scene.time.dt = dt;
  auto [resolved, model, settings] = prepare_scene(scene, file.string());
  Row row{scene.name, int(model.bodies.size()), model.num_dofs, int(model.nodes.T.rows()), int(model.mesh.F.rows()),
          dt, steps, 0, 0, 0, 0, 0, 0, 0};
  Simulation sim(std::move(model), settings);
  std::vector<double> ms, iterations, bp, ccd, assembly, solve;
  for (int k = 0; k < steps; ++k) {
    const StepStats s = sim.step();
    ms.push_back(1e3 * s.seconds);
    iterations.push_back(s.newton.iterations);
    bp.push_back(1e3 * s.times.broad_phase);
    ccd.push_back(1e3 * s.times.ccd);
    assembly.push_back(1e3 * s.times.assembly);
    solve.push_back(1e3 * s.times.solve);
    row.unconverged += s.newton.converged ? 0 : 1;
  }
  row.ms_median = median(ms);
  row.iterations = mean(iterations);
  row.broad_phase_ms = mean(bp);
  row.ccd_ms = mean(ccd);
  row.assembly_ms = mean(assembly);
  row.solve_ms = mean(solve);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"stiffsoft time-step benchmark on the seed's piles (light, medium, full) or any scenes, e.g. the hybrid ones"};
  std::vector<std::string> scenes{"light", "medium", "full"};
  std::vector<double> dts{1.0 / 100, 1.0 / 240, 1.0 / 1000};
  double duration = 0.25;
  int threads = 0;
  std::filesystem::path scene_dir = STIFFSOFT_SOURCE_DIR "/scenes", csv = "step_bench.csv";
  app.add_option("--scenes", scenes, "scene names in the scene folder")->delimiter(',');
  app.add_option("--dt", dts, "time steps (s)")->delimiter(',');
  app.add_option("--duration", duration, "simulated time per run (s); steps = duration / dt");
  app.add_option("--threads", threads, "worker threads (0: all cores)");
  app.add_option("--scene-dir", scene_dir, "folder of the scenes");
  app.add_option("--csv", csv, "CSV output file");
  CLI11_PARSE(app, argc, argv);
  std::unique_ptr<tbb::global_control> control;
  if (threads > 0) control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);

  std::ofstream out(csv);
  out << "scene,bodies,dofs,tets,triangles,dt,steps,unconverged,ms_per_step_median,newton_iterations_mean,broad_phase_ms,ccd_ms,assembly_ms,solve_ms\n";
  std::printf("| scene | bodies | DOFs | tets | triangles | h (s) | steps | ms/step (median) | Newton it./step | broad phase ms | CCD ms | assembly ms | solve ms | unconverged |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& name : scenes)
    for (double dt : dts) {
      const int steps = std::max(1, int(std::lround(duration / dt)));
      const Row r = run(scene_dir / (name + ".json"), dt, steps);
      std::printf("| %s | %d | %d | %d | %d | 1/%.0f | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %d |\n",
                  r.scene.c_str(), r.bodies, r.dofs, r.tets, r.triangles, 1 / r.dt, r.steps, r.ms_median, r.iterations, r.broad_phase_ms, r.ccd_ms,
                  r.assembly_ms, r.solve_ms, r.unconverged);
      std::fflush(stdout);
      out << r.scene << ',' << r.bodies << ',' << r.dofs << ',' << r.tets << ',' << r.triangles << ',' << r.dt << ',' << r.steps << ',' << r.unconverged
          << ',' << r.ms_median << ',' << r.iterations << ',' << r.broad_phase_ms << ',' << r.ccd_ms << ','
          << r.assembly_ms << ',' << r.solve_ms << '\n';
    }
  return 0;
}
