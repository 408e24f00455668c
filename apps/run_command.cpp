#include "run_command.hpp"

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <cmath>
#include <memory>
#include <optional>

#include <stiffsoft/coupling/linear_solver/petsc_session.hpp>
#include <stiffsoft/coupling/solver/physics_error.hpp>
#include <stiffsoft/io/checkpoint.hpp>
#include <stiffsoft/io/recorder.hpp>
#include <stiffsoft/scene/make_simulation.hpp>

#include "load_watchdog.hpp"
#include "progress.hpp"
#include "step_log.hpp"

namespace stiffsoft {

int run_scene(const RunOptions& options) {
  std::unique_ptr<tbb::global_control> threads;
  if (options.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, options.threads);

  SceneSimulation run = [&] {
    const LoadWatchdog bound(options.load_timeout, options.scene.string());
    return make_simulation(options.scene, options.limits);
  }();
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
  int first = 0;
  if (options.resume) {
    const Checkpoint checkpoint = read_checkpoint(options.out / "checkpoint.bin");
    if (PetscSession::rank() == 0)
      recorder.emplace(options.out, scene, sim, checkpoint, options.checkpoint_every);
    else
      sim.restore(checkpoint.state);
    first = checkpoint.state.step;
    spdlog::info("resuming at step {} (t = {:.4f} s) from {}", first, sim.time(), (options.out / "checkpoint.bin").string());
  } else if (PetscSession::rank() == 0) {
    recorder.emplace(options.out, scene, sim, options.checkpoint_every);
  }

  StepLog log;
  Progress progress(total);
  try {
    for (int k = first; k < total; ++k) {
      const StepStats s = sim.step();
      if (recorder) recorder->record(s, k + 1 == total);
      log.record(s, sim);
      if (recorder) progress.update(s.step, s.time, s.newton.iterations);
    }
  } catch (const PhysicsError& e) {
    // The step was not taken: everything written so far stays, up to the last good step.
    if (recorder) {
      progress.finish();
      recorder->finish();
    }
    spdlog::error("{}", e.what());
    if (recorder)
      spdlog::error("stopped: wrote {} frames to {} (up to t = {:.4f} s); {}", recorder->frame_count(),
                    recorder->pvd_path().string(), sim.time(), log.summary(sim.state().step - first));
    return 3;
  }
  if (!recorder) return log.unconverged() ? 3 : 0;
  progress.finish();
  recorder->finish();
  spdlog::info("wrote {} frames to {}; {}", recorder->frame_count(), recorder->pvd_path().string(), log.summary(total - first));
  return log.unconverged() ? 3 : 0;
}

}  // namespace stiffsoft
