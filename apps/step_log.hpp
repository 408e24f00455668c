#pragma once
/// @file What `stiffsoft run` says about its steps: at a sensible rate, through the logger.

#include <set>
#include <string>

#include <stiffsoft/coupling/solver/simulation.hpp>

namespace stiffsoft {

/// Logs what went wrong in the steps of a run, once per kind of event rather than every step:
/// Newton steps that did not converge (the first ten, then counted), linear-solver failures
/// (the first of each kind, then counted) and soft bodies with inverted tetrahedra (when they
/// appear in a body and when they are gone). The closing line counts them all.
class StepLog {
 public:
  /// Records step `s`, just taken by `sim`.
  void record(const StepStats& s, const Simulation& sim);
  /// The closing counts, e.g. "2 of 400 steps did not converge; linear-solver fallbacks in 3
  /// steps; inverted tetrahedra in 12 steps (at most 134, in 'foam')".
  std::string summary(int steps) const;
  /// Steps whose Newton did not converge.
  int unconverged() const { return m_unconverged; }

 private:
  int m_unconverged = 0;
  int m_linear_failures = 0;
  std::set<std::string> m_linear_kinds;       // failure texts already logged
  std::set<int> m_inverted_bodies;            // bodies with inverted tetrahedra at the last step
  int m_inverted_steps = 0, m_most_inverted = 0;
  std::string m_most_inverted_body;
};

}  // namespace stiffsoft
