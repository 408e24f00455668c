/// @file Linear-solver benchmark: every backend on the same Newton systems of growing size.
/// Systems come from running scenes (the rigid piles light / medium / full by default) for some
/// steps with CHOLMOD and keeping the densest Hessian each run assembled, from MatrixMarket
/// files (--systems-dir), and from synthetic soft lattices (--lattice, a stand-in for FEM
/// meshes of growing resolution). Per backend and system it reports set-up time (value copy +
/// factorisation or preconditioner, pattern reused), solve time, Krylov iterations and the
/// true relative residual, as a Markdown table on stdout and as CSV. `--dump DIR` writes the
/// systems in MatrixMarket. Runs under `mpirun -n N` too: every rank runs the same scenes and
/// PETSc backends solve distributed (rank 0 prints); CHOLMOD then runs redundantly per rank.

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <random>

#include <stiffsoft/coupling/linear_solver/cholmod_solver.hpp>
#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>
#include <stiffsoft/coupling/linear_solver/linear_system_io.hpp>
#include "apps/cli/petsc_command_line.hpp"
#include <stiffsoft/coupling/linear_solver/recording_solver.hpp>
#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene_loader.hpp>

#include "bench_statistics.hpp"

using namespace stiffsoft;

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

using stiffsoft::bench::median;

/// The densest system (most stored entries) a scene's Newton iterations produced in `steps` steps.
LinearSystem densest_system(const std::filesystem::path& file, int steps, double dt) {
  SceneDescription scene = load_scene(file);
  if (dt > 0) scene.time.dt = dt;
  auto [resolved, model, settings] = prepare_scene(scene, file.string());
  static LinearSystem* best = nullptr;
  static int step = 0;
  LinearSystem kept;
  best = &kept;
  register_linear_solver("bench-record", [] {
    return std::make_unique<RecordingSolver>(
        make_linear_solver("cholmod"),
        [](const Eigen::SparseMatrix<double>& upper, const Eigen::VectorXd& b) {
          if (upper.nonZeros() >= best->upper.nonZeros()) {
            best->upper = upper;
            best->b = b;
            best->name = "step" + std::to_string(step);
          }
        });
  });
  settings.linear_solver = "bench-record";
  Simulation sim(std::move(model), settings);
  for (step = 1; step <= steps; ++step) sim.step();
  kept.name = scene.name + "_" + kept.name;
  return kept;
}

/// A soft-body stand-in: a g×g×g lattice of nodes (spacing 1 cm, 1 g each, 3 DOFs) joined by
/// springs along the edges of the Kuhn tetrahedra of each cell (7 directions: 14 neighbours,
/// as in a tet mesh), H = M/h² + Σ k (d dᵀ + 0.1 I) on each spring's 2×2 blocks, h = 1e-2 s,
/// k = E·dx with E = 1e6 Pa; b random in [−1, 1] (fixed seed).
LinearSystem lattice_system(int g) {
  const int nodes = g * g * g, n = 3 * nodes;
  auto id = [g](int i, int j, int k) { return (i * g + j) * g + k; };
  const double mass = 1e-3, h = 1e-2, k_spring = 1e6 * 1e-2;
  std::vector<Eigen::Triplet<double>> t;
  for (int a = 0; a < nodes; ++a)
    for (int r = 0; r < 3; ++r) t.emplace_back(3 * a + r, 3 * a + r, mass / (h * h));
  const int dirs[7][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}, {1, 1, 1}};
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j)
      for (int k = 0; k < g; ++k)
        for (const auto& d : dirs) {
          if (i + d[0] >= g || j + d[1] >= g || k + d[2] >= g) continue;
          const int a = id(i, j, k), b = id(i + d[0], j + d[1], k + d[2]);
          const Eigen::Vector3d u = Eigen::Vector3d(d[0], d[1], d[2]).normalized();
          const Eigen::Matrix3d K = k_spring * (u * u.transpose() + 0.1 * Eigen::Matrix3d::Identity());
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
              if (r <= c) t.emplace_back(3 * a + r, 3 * a + c, K(r, c));
              if (r <= c) t.emplace_back(3 * b + r, 3 * b + c, K(r, c));
              t.emplace_back(3 * a + r, 3 * b + c, -K(r, c));  // a < b: upper triangle
            }
        }
  LinearSystem s;
  s.name = "lattice" + std::to_string(g);
  s.upper.resize(n, n);
  s.upper.setFromTriplets(t.begin(), t.end());
  s.upper.makeCompressed();
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  s.b.resize(n);
  for (double& x : s.b) x = u(rng);
  return s;
}

struct Row {
  std::string system, backend, status;
  int rows = 0, ranks = 1;
  long nonzeros = 0;
  double rtol = 0, analyze_ms = 0, setup_ms = 0, solve_ms = 0, residual = 0;
  double factor_flops = 0;  // CHOLMOD's prediction, for the "auto" rule
  int iterations = 0;
  bool fallback = false;
};

Row measure(const LinearSystem& s, const std::string& backend, double rtol, int repeat) {
  Row row{s.name, backend, "", int(s.upper.rows()), PetscSession::size(), long(s.upper.nonZeros()), rtol};
  std::unique_ptr<LinearSolver> solver = make_linear_solver(backend);
  solver->set_relative_tolerance(rtol);
  double t = now();
  solver->analyze_pattern(s.upper);
  row.analyze_ms = 1e3 * (now() - t);
  if (const auto* cholmod = dynamic_cast<const CholmodSolver*>(solver.get()))
    row.factor_flops = cholmod->factor_flops();
  // The repetitions alternate between H and (1 + 1e-9) H: a backend that keeps the columns
  // whose values did not change (block_cholesky) factorises the whole matrix every time, as in
  // a Newton iteration, instead of comparing values only.
  const Eigen::SparseMatrix<double> scaled = (1 + 1e-9) * s.upper;
  std::vector<double> setup, solve;
  for (int r = 0; r < repeat; ++r) {
    const Eigen::SparseMatrix<double>& H = r % 2 ? scaled : s.upper;
    t = now();
    const bool ok = solver->factorize(H);
    setup.push_back(1e3 * (now() - t));
    if (!ok) break;
    t = now();
    const Eigen::VectorXd p = solver->solve(s.b);
    solve.push_back(1e3 * (now() - t));
    // The residual is recomputed here, independently of the backend's report.
    row.residual = (s.b - H.selfadjointView<Eigen::Upper>() * p).norm() / s.b.norm();
  }
  const LinearSolveReport& report = solver->last_report();
  row.backend = solver->name();
  row.setup_ms = median(setup);
  row.solve_ms = median(solve);
  row.iterations = report.iterations;
  row.status = to_string(report.status);
  row.fallback = report.fallback_used;
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  PetscCommandLine petsc(argc, argv);
  const bool root = PetscSession::rank() == 0;
  CLI::App app{"stiffsoft linear-solver benchmark: every backend on the same Newton systems"};
  std::vector<std::string> scenes{"light", "medium", "full"};
  std::vector<int> lattices{10, 20, 30};
  std::vector<std::string> backends{
      "cholmod",       "petsc:cg:jacobi", "petsc:cg:pbjacobi",      "petsc:cg:vpbjacobi", "petsc:cg:icc",
      "petsc:cg:gamg", "petsc:cg:hypre",  "petsc:minres:vpbjacobi", "petsc:gmres:icc"};
  std::vector<double> rtols{1e-8, 1e-3};
  int steps = 40, repeat = 3, threads = 0;
  double dt = 0;
  std::filesystem::path scene_dir = STIFFSOFT_SOURCE_DIR "/scenes", csv = "linear_solver_bench.csv", dump,
                        systems_dir;
  std::vector<std::string> stored;
  app.add_option("--scenes", scenes, "scene names in the scene folder (empty: none)")->delimiter(',');
  app.add_option("--steps", steps, "steps run per scene; the densest Hessian is kept");
  app.add_option("--dt", dt, "time step override (s); 0: the scene's");
  app.add_option("--lattice", lattices, "synthetic soft lattices: nodes per side")->delimiter(',');
  app.add_option("--systems-dir", systems_dir, "folder of stored systems (NAME.mtx + NAME_b.mtx)");
  app.add_option("--systems", stored, "names of stored systems in --systems-dir")->delimiter(',');
  app.add_option("--backends", backends, "linear solvers (make_linear_solver names)")->delimiter(',');
  app.add_option("--rtol", rtols, "relative tolerances η of the Krylov solves")->delimiter(',');
  app.add_option("--repeat", repeat, "factorize+solve repetitions; times are medians");
  app.add_option("--threads", threads, "worker threads for the scene runs (0: all cores)");
  app.add_option("--scene-dir", scene_dir, "folder of the scenes");
  app.add_option("--csv", csv, "CSV output file (rank 0)");
  app.add_option("--dump", dump, "write the systems to this folder in MatrixMarket");
  CLI11_PARSE(app, petsc.program_argc(), petsc.program_argv());
  std::unique_ptr<tbb::global_control> control;
  if (threads > 0)
    control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);

  std::vector<LinearSystem> systems;
  // `--scenes ""` or `--lattice 0` turn a source off.
  for (const std::string& name : stored)
    if (!name.empty()) systems.push_back(load_linear_system(systems_dir, name));
  for (const std::string& name : scenes)
    if (!name.empty()) systems.push_back(densest_system(scene_dir / (name + ".json"), steps, dt));
  for (const int g : lattices)
    if (g > 1) systems.push_back(lattice_system(g));
  if (!dump.empty() && root)
    for (const LinearSystem& s : systems) save_linear_system(s, dump);

  std::ofstream out;
  if (root) {
    out.open(csv);
    out << "system,rows,nonzeros_upper,ranks,backend,rtol,analyze_ms,setup_ms,solve_ms,iterations,relative_"
           "residual,"
           "status,fallback,cholmod_factor_flops\n";
    std::printf(
        "| system | rows | nnz (upper) | ranks | backend | η | analyse ms | set-up ms | solve ms | "
        "iterations | ‖b−Hp‖/‖b‖ | status | CHOLMOD Mflop "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  }
  for (const LinearSystem& s : systems)
    for (const std::string& backend : backends)
      for (const double rtol : rtols) {
        if (backend == "cholmod" && rtol != rtols.front()) continue;  // direct: η does not apply
        Row r;
        try {
          r = measure(s, backend, rtol, repeat);
        } catch (const std::exception& e) {
          if (root) std::fprintf(stderr, "%s on %s: %s\n", backend.c_str(), s.name.c_str(), e.what());
          continue;
        }
        if (!root) continue;
        const bool direct = r.backend == "cholmod";
        char eta[16], mflop[16];
        std::snprintf(eta, sizeof eta, "%.0e", rtol);
        std::snprintf(mflop, sizeof mflop, "%.3g", 1e-6 * r.factor_flops);
        std::printf("| %s | %d | %ld | %d | %s | %s | %.2f | %.2f | %.2f | %d | %.1e | %s%s | %s |\n",
                    r.system.c_str(), r.rows, r.nonzeros, r.ranks, r.backend.c_str(), direct ? "–" : eta,
                    r.analyze_ms, r.setup_ms, r.solve_ms, r.iterations, r.residual, r.status.c_str(),
                    r.fallback ? " (fallback CHOLMOD)" : "", direct ? mflop : "");
        std::fflush(stdout);
        out << r.system << ',' << r.rows << ',' << r.nonzeros << ',' << r.ranks << ',' << r.backend << ','
            << (direct ? 0.0 : rtol) << ',' << r.analyze_ms << ',' << r.setup_ms << ',' << r.solve_ms << ','
            << r.iterations << ',' << r.residual << ',' << r.status << ',' << (r.fallback ? 1 : 0) << ','
            << r.factor_flops << '\n';
      }
  return 0;
}
