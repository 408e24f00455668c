#pragma once
/// @file Progress of a run: a one-line bar on a terminal, plain log lines otherwise.

#include <chrono>
#include <string>

namespace stiffsoft {

/// Reports step, simulated time, Newton iterations and ETA.
class Progress {
 public:
  /// `total` steps; a bar when standard error is a terminal, else a line every ~2 s.
  explicit Progress(int total);
  /// After step `step` (1-based) at simulated time `time` (s) with `iterations` Newton iterations.
  void update(int step, double time, int iterations);
  /// Ends the bar's line.
  void finish();

 private:
  int m_total;
  bool m_tty;
  std::chrono::steady_clock::time_point m_start, m_last;
};

}  // namespace stiffsoft
