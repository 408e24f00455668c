/// @file Whole-run linear-solver benchmark: each scene run for some steps with each backend, in
/// one process, measuring what a user feels — milliseconds per step, Newton iterations per
/// step, milliseconds per Newton iteration, per linear solve (set-up + solve), Krylov
/// iterations per solve, the relative residual of each step's last solve, and how far the end
/// state lies from the run with the first backend (the largest surface-point distance, m).
/// Scenes: the files named (rigid piles, hybrid scenes) and the soft scenes again at finer
/// `mesh_size` (--refine; bodies that set one), so the table spans from a hundred to tens of thousands of DOFs.
/// With --start T every run begins from the state the first backend reached at time T (one
/// untimed warm-up per scene, Simulation::state / restore), e.g. a pile in contact.
/// With --krylov-rtol-max every Krylov backend runs once per cap η_max of the forcing terms.
/// Under `mpirun -n N` every rank runs the scenes and the PETSc backends solve distributed
/// (CHOLMOD then solves redundantly on every rank); rank 0 prints and writes the CSV.
///
///     linear_solver_runs_bench --scenes light,medium,full,cube_on_mattress --steps 20
///     mpirun -n 2 linear_solver_runs_bench --scenes full --backends cholmod,petsc:cg:icc
///     linear_solver_runs_bench --scenes medium,full --start 0.6 --steps 10

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>

#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>
#include "apps/cli/petsc_command_line.hpp"
#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene_loader.hpp>

#include "bench_statistics.hpp"

using namespace stiffsoft;

namespace {

using stiffsoft::bench::median;

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / double(v.size());
}

/// What every linear solve of a run did, read from the backend's own report.
struct SolveLog {
  std::vector<double> ms;          ///< set-up + solve, per solve
  std::vector<double> iterations;  ///< Krylov iterations per solve
  double last_residual = 0;        ///< ‖b − H p‖/‖b‖ of the latest solve
  int fallbacks = 0;               ///< solves a fallback (CHOLMOD) finished
};

/// Passes everything to `inner` and logs each solve's report.
class LoggingSolver final : public LinearSolver {
 public:
  LoggingSolver(std::unique_ptr<LinearSolver> inner, SolveLog& log) : m_inner(std::move(inner)), m_log(log) {}
  void analyze_pattern(const Eigen::SparseMatrix<double>& upper) override { m_inner->analyze_pattern(upper); }
  bool factorize(const Eigen::SparseMatrix<double>& upper) override { return m_inner->factorize(upper); }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override {
    Eigen::VectorXd p = m_inner->solve(b);
    const LinearSolveReport& r = m_inner->last_report();
    m_report = r;
    m_log.ms.push_back(1e3 * (r.setup_seconds + r.solve_seconds));
    m_log.iterations.push_back(r.iterations);
    m_log.last_residual = r.relative_residual;
    m_log.fallbacks += r.fallback_used;
    return p;
  }
  std::string name() const override { return m_inner->name(); }
  void set_relative_tolerance(double eta) override { m_inner->set_relative_tolerance(eta); }
  bool is_iterative() const override { return m_inner->is_iterative(); }
  void set_block_sizes(const std::vector<int>& sizes) override { m_inner->set_block_sizes(sizes); }

 private:
  std::unique_ptr<LinearSolver> m_inner;
  SolveLog& m_log;
};

/// One scene × backend run.
struct RunRow {
  std::string scene, backend;
  int dofs = 0, tets = 0, steps = 0, ranks = 1, unconverged = 0, fallbacks = 0;
  double ms_step = 0, newton = 0, ms_newton = 0, ms_solve = 0, krylov = 0, residual = 0, deviation = 0;
};

/// A scene, possibly with every soft body's mesh_size scaled by `refine` (< 1: finer).
struct SceneCase {
  std::string label;
  std::filesystem::path file;
  double refine = 1;
};

/// The case's scene (refined, with the time step override) as a model and its settings.
std::pair<Model, SimulationSettings> build_case(const SceneCase& c, double dt) {
  SceneDescription scene = load_scene(c.file);
  if (dt > 0) scene.time.dt = dt;
  if (c.refine != 1)
    for (BodyDescription& b : scene.bodies)
      if (b.model == ModelChoice::Soft && b.mesh_size) *b.mesh_size *= c.refine;
  PreparedScene p = prepare_scene(scene, c.file.string());
  return {std::move(p.model), p.settings};
}

/// The state the case reaches at time `start` with `backend` (untimed warm-up).
SimulationState warm_up(const SceneCase& c, const std::string& backend, double dt, double start) {
  auto [model, settings] = build_case(c, dt);
  settings.linear_solver = backend;
  Simulation sim(std::move(model), settings);
  const int steps = int(std::lround(start / settings.h));
  for (int k = 0; k < steps; ++k) sim.step();
  return sim.state();
}

/// One backend, and for a Krylov backend the forcing terms' cap η_max (unset: the scene's).
struct BackendCase {
  std::string name;
  std::optional<double> rtol_max;
  std::string label() const {
    if (!rtol_max) return name;
    char text[32];
    std::snprintf(text, sizeof text, " (η_max %g)", *rtol_max);
    return name + text;
  }
};

RunRow run_case(const SceneCase& c, const BackendCase& b, int steps, double dt,
                const std::optional<SimulationState>& start, Eigen::MatrixX3d& end_surface) {
  auto [model, settings] = build_case(c, dt);
  const std::string& backend = b.name;
  if (b.rtol_max) settings.krylov_rtol_max = *b.rtol_max;
  static SolveLog* log = nullptr;
  static std::string inner;
  SolveLog kept;
  log = &kept;
  inner = backend;
  register_linear_solver("bench-log", [] { return std::make_unique<LoggingSolver>(make_linear_solver(inner), *log); });
  settings.linear_solver = "bench-log";

  RunRow row;
  row.scene = c.label;
  if (start) {
    char from[48];
    std::snprintf(from, sizeof from, " from t = %g s", start->time);
    row.scene += from;
  }
  row.backend = b.label();
  row.dofs = model.num_dofs;
  row.tets = int(model.nodes.T.rows());
  row.ranks = PetscSession::size();
  Simulation sim(std::move(model), settings);
  if (start) sim.restore(*start);
  std::vector<double> ms, newton, residuals;
  for (int k = 0; k < steps; ++k) {
    const StepStats s = sim.step();
    ms.push_back(1e3 * s.seconds);
    newton.push_back(s.newton.iterations);
    residuals.push_back(kept.last_residual);
    row.unconverged += !s.newton.converged;
  }
  row.steps = steps;
  row.ms_step = median(ms);
  row.newton = mean(newton);
  double total_ms = 0, total_newton = 0;
  for (std::size_t k = 0; k < ms.size(); ++k) total_ms += ms[k], total_newton += newton[k];
  row.ms_newton = total_newton > 0 ? total_ms / total_newton : 0;
  row.ms_solve = median(kept.ms);
  row.krylov = mean(kept.iterations);
  row.residual = median(residuals);
  row.fallbacks = kept.fallbacks;
  end_surface = sim.surface();
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  PetscCommandLine petsc(argc, argv);
  const bool root = PetscSession::rank() == 0;
  CLI::App app{"stiffsoft whole-run linear-solver benchmark: each scene with each backend"};
  std::vector<std::string> scenes{"light", "medium", "full", "mixed_pile", "cube_on_mattress"};
  std::vector<double> refine{0.7, 0.5};
  std::vector<std::string> backends{"cholmod", "petsc:cg:icc", "petsc:cg:vpbjacobi", "petsc:cg:gamg", "auto"};
  std::vector<double> rtol_max;
  int steps = 20, threads = 0;
  double dt = 0, start = 0;
  std::filesystem::path scene_dir = STIFFSOFT_SOURCE_DIR "/scenes", csv = "linear_solver_runs.csv";
  app.add_option("--scenes", scenes, "scene names in the scene folder")->delimiter(',');
  app.add_option("--refine", refine, "soft scenes are run again with mesh_size × each factor")->delimiter(',');
  app.add_option("--backends", backends, "linear solvers (make_linear_solver names); the first is the reference")
      ->delimiter(',');
  app.add_option("--krylov-rtol-max", rtol_max,
                 "run every Krylov backend once per forcing-term cap η_max (default: the scene's)")
      ->delimiter(',');
  app.add_option("--steps", steps, "steps per run");
  app.add_option("--dt", dt, "time step override (s); 0: the scene's");
  app.add_option("--start", start, "simulated time (s) reached with the first backend before the timed steps");
  app.add_option("--threads", threads, "worker threads (0: all cores)");
  app.add_option("--scene-dir", scene_dir, "folder of the scenes");
  app.add_option("--csv", csv, "CSV output file (rank 0)");
  CLI11_PARSE(app, petsc.program_argc(), petsc.program_argv());
  std::unique_ptr<tbb::global_control> control;
  if (threads > 0)
    control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);

  std::vector<SceneCase> cases;
  for (const std::string& name : scenes) {
    const std::filesystem::path file = scene_dir / (name + ".json");
    cases.push_back({name, file, 1});
    bool soft = false;
    for (const BodyDescription& b : load_scene(file).bodies) soft |= b.model == ModelChoice::Soft && b.mesh_size;
    if (soft)
      for (const double f : refine) {
        char label[64];
        std::snprintf(label, sizeof label, "%s ×%.2g", name.c_str(), f);
        cases.push_back({label, file, f});
      }
  }

  std::vector<BackendCase> runs;
  for (const std::string& name : backends) {
    const bool krylov = name != "cholmod";  // auto may pick PETSc
    if (!krylov || rtol_max.empty()) runs.push_back({name, std::nullopt});
    else
      for (const double eta : rtol_max) runs.push_back({name, eta});
  }

  std::ofstream out;
  if (root) {
    out.open(csv);
    out << "scene,dofs,tets,ranks,backend,steps,ms_per_step,newton_per_step,ms_per_newton,ms_per_solve,"
           "krylov_per_solve,relative_residual,unconverged_steps,fallbacks,deviation_m\n";
    std::printf(
        "| scene | DOFs | tets | ranks | backend | ms/step | Newton it./step | ms/Newton it. | ms/solve | Krylov it./solve | "
        "last ‖b−Hp‖/‖b‖ | unconverged | deviation (m) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  }
  for (const SceneCase& c : cases) {
    Eigen::MatrixX3d reference;
    std::optional<SimulationState> state;
    if (start > 0) {
      const auto t0 = std::chrono::steady_clock::now();
      state = warm_up(c, backends.front(), dt, start);
      if (root)
        std::fprintf(stderr, "%s: warm-up to t = %g s with %s took %.0f s\n", c.label.c_str(), state->time,
                     backends.front().c_str(),
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    for (std::size_t i = 0; i < runs.size(); ++i) {
      Eigen::MatrixX3d end;
      RunRow r;
      try {
        r = run_case(c, runs[i], steps, dt, state, end);
      } catch (const std::exception& e) {
        if (root) std::fprintf(stderr, "%s on %s: %s\n", runs[i].label().c_str(), c.label.c_str(), e.what());
        continue;
      }
      if (i == 0) reference = end;
      if (reference.rows() == end.rows()) r.deviation = (end - reference).rowwise().norm().maxCoeff();
      if (!root) continue;
      std::printf("| %s | %d | %d | %d | %s | %.2f | %.2f | %.2f | %.3f | %.1f | %.1e | %d | %.1e |\n",
                  r.scene.c_str(), r.dofs, r.tets, r.ranks, r.backend.c_str(), r.ms_step, r.newton, r.ms_newton,
                  r.ms_solve, r.krylov, r.residual, r.unconverged, r.deviation);
      std::fflush(stdout);
      out << '"' << r.scene << "\"," << r.dofs << ',' << r.tets << ',' << r.ranks << ',' << r.backend << ','
          << r.steps << ',' << r.ms_step << ',' << r.newton << ',' << r.ms_newton << ',' << r.ms_solve << ','
          << r.krylov << ',' << r.residual << ',' << r.unconverged << ',' << r.fallbacks << ',' << r.deviation
          << '\n';
    }
  }
  return 0;
}
