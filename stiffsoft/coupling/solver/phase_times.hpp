#pragma once
/// @file Wall-clock seconds spent per phase of a time step, for stats and benchmarks.

#include <chrono>

namespace stiffsoft {

/// Seconds per phase, accumulated over one step.
struct PhaseTimes {
  double broad_phase = 0;  ///< candidate search and active-set construction (s)
  double ccd = 0;          ///< continuous collision detection bounding line-search steps (s)
  double assembly = 0;     ///< gradients and Hessians (s)
  double solve = 0;        ///< linear solves (s)
};

/// Adds the lifetime of the guard to a PhaseTimes field.
class ScopedTimer {
 public:
  /// Starts timing into `seconds`.
  explicit ScopedTimer(double& seconds) : m_seconds(seconds), m_start(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() {
    m_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& m_seconds;
  std::chrono::steady_clock::time_point m_start;
};

}  // namespace stiffsoft
