#include "run_command.hpp"

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <cmath>
#include <memory>
#include <optional>

#include <stiffsoft/coupling/linear_solver/petsc_session.hpp>
#include <stiffsoft/io/recorder.hpp>
#include <stiffsoft/scene/make_simulation.hpp>

#include "progress.hpp"

namespace stiffsoft {

int run_scene(const RunOptions& options) {
  std::unique_ptr<tbb::global_control> threads;
  if (options.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, options.threads);

  SceneSimulation run = make_simulation(options.scene);
  const SceneDescription& scene = run.scene;
  Simulation& sim = run.simulation;
  const Model& model = sim.model();
  const SimulationSettings& settings = sim.settings();
  const int total = options.steps ? *options.steps : int(std::ceil(scene.time.duration / scene.time.dt - 1e-9));
  spdlog::info("{}: {} bodies, {} DOFs, {} triangles; h = {} s, d̂ = {:.3g} m, ε_v = {:.3g} m/s, ε_d = {:.3g} m/s, {} steps",
               scene.name, model.bodies.size(), model.num_dofs, model.mesh.F.rows(), settings.h, settings.dhat,
               settings.eps_v, settings.tolerance, total);

  // Under MPI every rank simulates (the linear solve is shared); rank 0 alone writes.
  std::optional<Recorder> recorder;
  if (PetscSession::rank() == 0) recorder.emplace(options.out, scene, sim);

  int failed = 0;
  Progress progress(total);
  for (int k = 0; k < total; ++k) {
    const StepStats s = sim.step();
    if (recorder) recorder->record(s, k + 1 == total);
    if (!s.newton.linear_failure.empty())
      spdlog::warn("step {} (t = {:.4f} s): linear solver ({}) failed at {}", s.step, s.time, settings.linear_solver,
                   s.newton.linear_failure);
    if (!s.newton.converged) {
      ++failed;
      spdlog::warn("step {} (t = {:.4f} s): Newton did not converge after {} iterations: {} (last step speed {:.3g} m/s, tolerance {:.3g} m/s)",
                   s.step, s.time, s.newton.iterations, s.newton.failure, s.newton.last_step_speed, settings.tolerance);
    }
    if (recorder) progress.update(s.step, s.time, s.newton.iterations);
  }
  if (!recorder) return failed ? 3 : 0;
  progress.finish();
  recorder->finish();
  spdlog::info("wrote {} frames to {}; {} of {} steps did not converge", recorder->frame_count(),
               recorder->pvd_path().string(), failed, total);
  return failed ? 3 : 0;
}

}  // namespace stiffsoft
