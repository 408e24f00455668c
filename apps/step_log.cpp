#include "step_log.hpp"

#include <spdlog/spdlog.h>

namespace stiffsoft {

namespace {
constexpr int kLoggedUnconverged = 10;  // non-converged steps logged one by one

/// A linear-solver failure without its iteration ("iteration 3: CHOLMOD: …" → "CHOLMOD: …").
std::string failure_kind(const std::string& failure) {
  const std::size_t colon = failure.find(": ");
  return colon == std::string::npos ? failure : failure.substr(colon + 2);
}
}  // namespace

void StepLog::record(const StepStats& s, const Simulation& sim) {
  if (!s.newton.linear_failure.empty()) {
    ++m_linear_failures;
    const std::string kind = failure_kind(s.newton.linear_failure);
    if (m_linear_kinds.insert(kind).second)
      spdlog::warn("step {} (t = {:.4f} s, {} bodies): linear solver ({}) failed: {} (logged once; every "
                   "step's fallbacks are in stats.csv, linear_fallbacks)",
                   s.step, s.time, sim.model().bodies.size(), sim.settings().linear_solver, s.newton.linear_failure);
  }
  if (!s.newton.converged) {
    ++m_unconverged;
    if (m_unconverged <= kLoggedUnconverged)
      spdlog::warn("step {} (t = {:.4f} s): Newton did not converge after {} iterations: {} (last step speed "
                   "{:.3g} m/s, tolerance {:.3g} m/s){}",
                   s.step, s.time, s.newton.iterations, s.newton.failure, s.newton.last_step_speed,
                   sim.settings().tolerance,
                   m_unconverged == kLoggedUnconverged ? "; further ones are only counted" : "");
  }
  std::set<int> inverted;
  if (s.inverted_tets > 0) {
    ++m_inverted_steps;
    const std::vector<int>& counts = s.inverted_per_body;
    for (int b = 0; b < int(counts.size()); ++b) {
      if (counts[b] == 0) continue;
      const std::string& name = sim.model().bodies[b].name;
      inverted.insert(b);
      if (!m_inverted_bodies.count(b))
        spdlog::warn("step {} (t = {:.4f} s): soft body '{}' has {} inverted tetrahedra (det F ≤ 0): the "
                     "material is compressed beyond what it models; refine the mesh, stiffen the material or "
                     "lighten the load (counts per step: inverted_tets in stats.csv)",
                     s.step, s.time, name, counts[b]);
      if (counts[b] > m_most_inverted) {
        m_most_inverted = counts[b];
        m_most_inverted_body = name;
      }
    }
  }
  for (int b : m_inverted_bodies)
    if (!inverted.count(b))
      spdlog::info("step {} (t = {:.4f} s): soft body '{}' has no inverted tetrahedra any more", s.step, s.time,
                   sim.model().bodies[b].name);
  m_inverted_bodies = std::move(inverted);
}

std::string StepLog::summary(int steps) const {
  std::string text = std::to_string(m_unconverged) + " of " + std::to_string(steps) + " steps did not converge";
  if (m_linear_failures > 0)
    text += "; linear-solver fallbacks or failures in " + std::to_string(m_linear_failures) + " steps";
  if (m_inverted_steps > 0)
    text += "; inverted tetrahedra in " + std::to_string(m_inverted_steps) + " steps (at most " +
            std::to_string(m_most_inverted) + ", in '" + m_most_inverted_body + "')";
  return text;
}

}  // namespace stiffsoft
