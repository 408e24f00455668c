/// @file The linear-solver choice at the scene level: CHOLMOD and PETSc CG + GAMG give the same
/// trajectory within Newton's tolerance; PETSc options given to `stiffsoft run` reach PETSc;
/// `mpirun -n 2 stiffsoft run` reproduces the serial run (when mpirun is installed).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "apps/cli/petsc_arguments.hpp"

#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft//io/frame_reader.hpp>
#include "scene_helpers.hpp"

using namespace stiffsoft;
using namespace stiffsoft::testing;
namespace fs = std::filesystem;

namespace {

/// Surface positions after each of `steps` steps of a shipped scene solved by `backend`,
/// and the scene's Newton tolerance ε_d (m/s) and h (s).
struct Trajectory {
  std::vector<Eigen::MatrixX3d> x;
  double tolerance = 0, h = 0;
  int unconverged = 0;
};

Trajectory trajectory(const std::string& scene_name, const std::string& backend, int steps) {
  const fs::path file = fs::path(STIFFSOFT_SOURCE_DIR) / "scenes" / (scene_name + ".json");
  SceneDescription scene = load_scene(file);
  scene.solver.linear = backend;
  SceneSimulation run = make_simulation(scene, file.string());
  Simulation& sim = run.simulation;
  Trajectory t;
  t.tolerance = sim.settings().tolerance;
  t.h = sim.settings().h;
  for (int k = 0; k < steps; ++k) {
    t.unconverged += !sim.step().newton.converged;
    t.x.push_back(sim.surface());
  }
  return t;
}

/// A copy of a shipped scene in `dir` with solver.linear set to `backend`.
fs::path scene_with_solver(const std::string& scene_name, const std::string& backend, const fs::path& dir) {
  nlohmann::json j = nlohmann::json::parse(read_text(fs::path(STIFFSOFT_SOURCE_DIR) / "scenes" / (scene_name + ".json")));
  j["solver"]["linear"] = backend;
  const fs::path out = dir / (scene_name + ".json");
  std::ofstream(out) << j.dump(2);
  return out;
}

/// The points of every block of a run's last frame, stacked.
Eigen::MatrixXd last_frame(const fs::path& pvd) {
  const std::vector<PvdEntry> entries = read_pvd(pvd);
  std::vector<Eigen::MatrixX3d> blocks;
  int rows = 0;
  for (const NamedSurface& s : read_frame(entries.back().file)) {
    blocks.push_back(s.x);
    rows += int(s.x.rows());
  }
  Eigen::MatrixXd x(rows, 3);
  rows = 0;
  for (const Eigen::MatrixX3d& b : blocks) {
    x.middleRows(rows, b.rows()) = b;
    rows += int(b.rows());
  }
  return x;
}

/// `env -u VAR …` for every MPI launcher variable of this process: once a PETSc backend has
/// started MPI here (as a singleton), a child `mpirun` must not inherit its environment.
std::string without_mpi_environment() {
  std::string command = "env";
  for (const std::string& name : mpi_launcher_variables()) command += " -u " + name;
  return command;
}

}  // namespace

// Both runs stop each step once Newton's last surface step is below ε_d h, so each step's
// result lies within about ε_d h of the exact minimiser. On a well-posed motion (a stack
// settling, a box landing on a mattress) backward Euler does not amplify the difference, so
// after k steps the two trajectories must agree to 2 k ε_d h. (Tumbling piles are chaotic:
// on `light` the two runs are 4.8 cm apart after 40 steps, 14 times that bound, as two runs
// of any simulator differing at round-off level would be; they are not used here.)
TEST(LinearSolverChoice, CholmodAndPetscGamgTrajectoriesAgreeWithinNewtonsTolerance) {
  for (const auto& [scene, steps] : {std::pair<std::string, int>{"box_stack", 40}, {"cube_on_mattress", 12}}) {
    SCOPED_TRACE(scene);
    const Trajectory direct = trajectory(scene, "cholmod", steps);
    const Trajectory krylov = trajectory(scene, "petsc:cg:gamg", steps);
    EXPECT_EQ(direct.unconverged, 0);
    EXPECT_EQ(krylov.unconverged, 0);
    double worst_ratio = 0;
    for (int k = 0; k < steps; ++k) {
      const double gap = (direct.x[k] - krylov.x[k]).rowwise().norm().maxCoeff();
      const double bound = 2.0 * (k + 1) * direct.tolerance * direct.h;
      worst_ratio = std::max(worst_ratio, gap / bound);
      EXPECT_LE(gap, bound) << "step " << k + 1;
    }
    std::printf("[ %s ] largest surface gap / (2 k ε_d h) over %d steps: %.3g\n", scene.c_str(), steps, worst_ratio);
  }
}

TEST(LinearSolverChoice, PetscOptionsOnTheCommandLineReachPetsc) {
  const fs::path dir = temporary_folder("stiffsoft_petsc_options");
  const fs::path scene = scene_with_solver("cube_on_mattress", "petsc", dir);
  ASSERT_EQ(run_stiffsoft("run " + scene.string() + " -o " + (dir / "out").string() +
                              " --steps 2 -ksp_type minres -ksp_monitor -log_view",
                          dir / "run.log"),
            0)
      << read_text(dir / "run.log");
  const std::string log = read_text(dir / "run.log");
  EXPECT_NE(log.find("KSP Residual norm"), std::string::npos) << log.substr(0, 2000);
  EXPECT_NE(log.find("minres"), std::string::npos) << "-log_view names the KSP type";
  EXPECT_NE(log.find("Performance Summary"), std::string::npos);
  fs::remove_all(dir);
}

// Every rank simulates; the linear solve is shared (MPI BAIJ/SBAIJ, block Jacobi with ICC on
// each rank's rows), so the runs differ only by the Krylov method's rounding and preconditioner
// within Newton's tolerance. Only rank 0 writes.
TEST(LinearSolverChoice, TwoMpiRanksReproduceTheSerialRun) {
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0) GTEST_SKIP() << "no mpirun";
  const fs::path dir = temporary_folder("stiffsoft_mpi_run");
  const fs::path scene = scene_with_solver("cube_on_mattress", "petsc:cg:icc", dir);
  const int steps = 10;
  const std::string args = "run " + scene.string() + " --steps " + std::to_string(steps) + " -o ";
  ASSERT_EQ(run_stiffsoft(args + (dir / "serial").string(), dir / "serial.log"), 0) << read_text(dir / "serial.log");
  const std::string mpi = without_mpi_environment() + " timeout 600 mpirun --allow-run-as-root --oversubscribe -n 2 " +
                          std::string(STIFFSOFT_BINARY) + " " + args + (dir / "mpi").string() + " > " +
                          (dir / "mpi.log").string() + " 2>&1";
  ASSERT_EQ(std::system(mpi.c_str()), 0) << read_text(dir / "mpi.log");

  const std::vector<double> converged = csv_column(dir / "mpi" / "stats.csv", "converged");
  ASSERT_EQ(int(converged.size()), steps) << "rank 0 wrote one row per step, once";
  for (double c : converged) EXPECT_EQ(c, 1.0);
  const Eigen::MatrixXd serial = last_frame(dir / "serial" / "cube_on_mattress.pvd");
  const Eigen::MatrixXd parallel = last_frame(dir / "mpi" / "cube_on_mattress.pvd");
  ASSERT_EQ(serial.rows(), parallel.rows());
  const nlohmann::json resolved = nlohmann::json::parse(read_text(dir / "serial" / "scene.resolved.json"));
  const double bound = 2.0 * steps * resolved["solver"]["tolerance"].get<double>() * resolved["time"]["dt"].get<double>();
  const double gap = (serial - parallel).rowwise().norm().maxCoeff();
  std::printf("[ mpirun -n 2 ] largest surface gap after %d steps: %.3g m (bound 2 k ε_d h = %.3g m)\n", steps, gap,
              bound);
  EXPECT_LE(gap, bound);
  fs::remove_all(dir);
}
