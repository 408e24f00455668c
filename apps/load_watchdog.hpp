#pragma once
/// @file A time bound on loading and meshing a scene: a .geo file is a gmsh script, which can
/// loop or mesh itself without end, and no estimate made before running it can bound it.

#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace stiffsoft {

/// While alive, ends the process (exit code 2, an error naming `what` and the bound) should it
/// live longer than `seconds`; nothing has been written yet while a scene loads, so nothing is
/// lost. `seconds` ≤ 0: no bound.
class LoadWatchdog {
 public:
  /// Starts the bound.
  LoadWatchdog(double seconds, std::string what);
  /// Stops it.
  ~LoadWatchdog();
  LoadWatchdog(const LoadWatchdog&) = delete;
  LoadWatchdog& operator=(const LoadWatchdog&) = delete;

 private:
  std::mutex m_mutex;
  std::condition_variable m_done_changed;
  bool m_done = false;
  std::thread m_thread;
};

}  // namespace stiffsoft
