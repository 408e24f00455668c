#pragma once
/// @file Settings of the conservative linear continuous collision detection (CCD).

#include <limits>

namespace stiffsoft::ccd {

/// Settings of the conservative CCD (Additive CCD, Li, Kaufman, Jiang 2021, §5).
struct CcdSettings {
  double min_distance = 0;     ///< ξ ≥ 0: distances below this count as contact (m)
  double tolerance = 0.1;      ///< s ∈ (0,1): the returned time keeps a gap ≥ s·(initial distance − ξ)
  int max_iterations = 1000;   ///< cap ≥ 1; on reaching it, report a collision at the last safe time
  double t_max = 1.0;          ///< only look in [0, t_max], 0 ≤ t_max ≤ 1
};

/// Throws std::invalid_argument naming the offending field (called by validate()).
[[noreturn]] void throw_out_of_range(const CcdSettings& settings);

/// Throws std::invalid_argument naming the offending field when `settings` is out of range.
/// Inline: every query checks its settings, and the check is a few compares.
inline void validate(const CcdSettings& settings) {
  const bool in_range = settings.min_distance >= 0 && settings.min_distance < std::numeric_limits<double>::infinity() &&
                        settings.tolerance > 0 && settings.tolerance < 1 && settings.max_iterations >= 1 &&
                        settings.t_max > 0 && settings.t_max <= 1;
  if (!in_range) throw_out_of_range(settings);
}

}  // namespace stiffsoft::ccd
