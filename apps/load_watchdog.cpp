#include "load_watchdog.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdlib>

namespace stiffsoft {

LoadWatchdog::LoadWatchdog(double seconds, std::string what) {
  if (!(seconds > 0)) return;
  m_thread = std::thread([this, seconds, what = std::move(what)] {
    std::unique_lock lock(m_mutex);
    if (m_done_changed.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return m_done; })) return;
    spdlog::error("{}: loading and meshing the scene took longer than {} s: a gmsh .geo script that loops or "
                  "meshes itself without end, or a mesh far finer than intended? Raise the bound with "
                  "`stiffsoft run --load-timeout SECONDS` (0: none) if the scene is meant to be this large",
                  what, seconds);
    spdlog::default_logger()->flush();
    std::_Exit(2);
  });
}

LoadWatchdog::~LoadWatchdog() {
  if (!m_thread.joinable()) return;
  {
    std::lock_guard lock(m_mutex);
    m_done = true;
  }
  m_done_changed.notify_all();
  m_thread.join();
}

}  // namespace stiffsoft
