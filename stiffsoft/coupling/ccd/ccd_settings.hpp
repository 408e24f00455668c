#pragma once
/// @file Settings of the conservative linear continuous collision detection (CCD).

#include <cmath>
#include <string>

namespace stiffsoft::ccd {

/// Settings of the conservative CCD (Additive CCD, Li, Kaufman, Jiang 2021, §5).
struct CcdSettings {
  double min_distance = 0;     ///< ξ ≥ 0: distances below this count as contact (m)
  double tolerance = 0.1;      ///< s ∈ (0,1): the returned time keeps a gap ≥ s·(initial distance − ξ)
  int max_iterations = 1000;   ///< cap ≥ 1; on reaching it, report a collision at the last safe time
  double t_max = 1.0;          ///< only look in [0, t_max], 0 ≤ t_max ≤ 1
};

/// Throws std::invalid_argument "CcdSettings.<field_and_requirement>, got <value>" (out of
/// line: validate() runs in every query, the message almost never).
[[noreturn]] void throw_invalid(const char* field_and_requirement, const std::string& value);

/// Throws std::invalid_argument naming the offending field when `settings` is out of range.
/// Inline: every query checks its settings, and the check is a few compares.
inline void validate(const CcdSettings& settings) {
  if (!(settings.min_distance >= 0) || !std::isfinite(settings.min_distance))
    throw_invalid("min_distance: must be finite and >= 0", std::to_string(settings.min_distance));
  if (!(settings.tolerance > 0 && settings.tolerance < 1))
    throw_invalid("tolerance: must be in (0, 1)", std::to_string(settings.tolerance));
  if (settings.max_iterations < 1)
    throw_invalid("max_iterations: must be >= 1", std::to_string(settings.max_iterations));
  if (!(settings.t_max > 0 && settings.t_max <= 1))
    throw_invalid("t_max: must be in (0, 1]", std::to_string(settings.t_max));
}

}  // namespace stiffsoft::ccd
