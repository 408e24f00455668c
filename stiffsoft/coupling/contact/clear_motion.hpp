#pragma once
/// @file Which candidate pairs of a move need no CCD query: those no closer than their vertices'
/// clearance that move too little to close it (the test ACCD's first step makes, from bounds
/// known before any pair's distance is computed).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <vector>

#include <stiffsoft/coupling/ccd/ccd_settings.hpp>
#include <stiffsoft/coupling/contact/constraint_set.hpp>

namespace stiffsoft {

/// For a straight-line move x0 → x1 of the surface (|V|×3, m) with the active contacts at x0.
/// Additive CCD (ccd/additive_ccd.hpp) returns its t_max for a pair whose first step,
/// (1 − s)(d₀ − ξ) / l_p, reaches t_max ≤ 1. With
///  - d₀ ≥ c, the smallest clearance of the pair's vertices: min(d̂, the distance of the nearest
///    active contact holding the vertex). A pair closer than d̂ at x0 is an active contact
///    holding one vertex of each primitive, at the pair's own distance;
///  - l_p ≤ 4 r, r the largest distance one of its vertices moves (ACCD's l_p sums the two
///    primitives' largest speeds relative to the mean of the four, each at most 2 r);
/// the first step reaches 1 when (1 − s)(c − ξ) ≥ 4 r, with margins for rounding: at rest most
/// pairs of a pile qualify by orders of magnitude.
class ClearMotion {
 public:
  /// `constraints`: every pair closer than `dhat` (m) at x0, with its distance there
  /// (build_constraints at x0: BarrierTerm's active set); `settings`: the queries' CCD settings
  /// (s, ξ; t_max is each query's own).
  ClearMotion(const std::vector<ContactConstraint>& constraints, const Eigen::MatrixX3d& x0,
              const Eigen::MatrixX3d& x1, double dhat, const ccd::CcdSettings& settings);
  /// True when ACCD over the pair with these surface vertices (the first always one, −1 for
  /// none after it) is certain to return its t_max: the query can be skipped with the same result.
  bool is_clear(const std::array<int, 4>& vertices) const {
    double clearance = m_clearance[std::size_t(vertices[0])], reach = m_reach[std::size_t(vertices[0])];
    for (int i = 1; i < 4; ++i)
      if (vertices[i] >= 0) {
        clearance = std::min(clearance, m_clearance[std::size_t(vertices[i])]);
        reach = std::max(reach, m_reach[std::size_t(vertices[i])]);
      }
    return m_keep * (clearance * (1 - kRelativeMargin) - m_allowance) >= 4 * reach * (1 + kRelativeMargin);
  }

 private:
  /// Relative rounding margin on the clearance and the reach: far above the distance formulas'
  /// differences (the contact's classified distance against ACCD's primitive distance).
  static constexpr double kRelativeMargin = 1e-6;
  std::vector<double> m_clearance;  ///< per vertex, m
  std::vector<double> m_reach;      ///< per vertex, ‖x1 − x0‖, m
  double m_allowance = 0;           ///< ξ plus twice ACCD's largest rounding allowance over the move, m
  double m_keep = 0;                ///< 1 − s
};

}  // namespace stiffsoft
