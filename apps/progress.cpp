#include "progress.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>

namespace stiffsoft {

Progress::Progress(int total)
    : m_total(total), m_tty(isatty(fileno(stderr))), m_start(std::chrono::steady_clock::now()), m_last(m_start) {}

void Progress::update(int step, double time, int iterations) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - m_start).count();
  const double eta = step > 0 ? elapsed / step * (m_total - step) : 0.0;
  if (m_tty) {
    const int width = 30, filled = m_total > 0 ? width * step / m_total : width;
    std::fprintf(stderr, "\r[%s%s] step %d/%d  t=%.4f s  newton %d  ETA %.0f s   ",
                 std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), step, m_total,
                 time, iterations, eta);
    std::fflush(stderr);
  } else if (std::chrono::duration<double>(now - m_last).count() > 2.0 || step == m_total) {
    spdlog::info("step {}/{}  t={:.4f} s  newton {}  ETA {:.0f} s", step, m_total, time, iterations, eta);
    m_last = now;
  }
}

void Progress::finish() {
  if (m_tty) std::fprintf(stderr, "\n");
}

}  // namespace stiffsoft
