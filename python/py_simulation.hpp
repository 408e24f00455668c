#pragma once
/// @file What a Python `Simulation` and `Recorder` hold.

#include <atomic>
#include <memory>
#include <optional>

#include "bindings.hpp"

namespace stiffsoft::python {

/// A Simulation with the resolved scene it came from. Not copyable or movable (neither is a
/// Simulation): Python holds it by pointer.
struct PySimulation {
  /// Constructs the simulation in place from a prepared scene.
  explicit PySimulation(PreparedScene prepared)
      : scene(std::move(prepared.scene)), simulation(std::move(prepared.model), prepared.settings) {}
  SceneDescription scene;        ///< the scene with every default resolved
  Simulation simulation;         ///< the simulation
  std::atomic<bool> busy{false};  ///< a step is running (with the GIL released)
};

/// Marks a PySimulation busy for its lifetime; a RuntimeError if it is already (another Python
/// thread is stepping it).
class Busy {
 public:
  /// Marks `s` busy.
  explicit Busy(PySimulation& s);
  ~Busy() { m_s.busy = false; }
  Busy(const Busy&) = delete;
  Busy& operator=(const Busy&) = delete;

 private:
  PySimulation& m_s;
};

/// A Recorder of a PySimulation (the Python object keeps the simulation alive).
struct PyRecorder {
  std::unique_ptr<Recorder> recorder;  ///< null once finished
};

/// Takes one step with the GIL released; then raises a pending KeyboardInterrupt (Ctrl-C)
/// and other signals' exceptions, after the step. `recorder` (may be null) records it.
StepStats take_step(PySimulation& s, PyRecorder* recorder, bool last);

}  // namespace stiffsoft::python
