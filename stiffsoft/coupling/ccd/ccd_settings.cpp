#include <stiffsoft/coupling/ccd/ccd_settings.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

namespace stiffsoft::ccd {

void throw_out_of_range(const CcdSettings& settings) {
  if (!(settings.min_distance >= 0) || !std::isfinite(settings.min_distance)) {
    throw std::invalid_argument("CcdSettings.min_distance: must be finite and >= 0, got " +
                                std::to_string(settings.min_distance));
  }
  if (!(settings.tolerance > 0 && settings.tolerance < 1)) {
    throw std::invalid_argument("CcdSettings.tolerance: must be in (0, 1), got " +
                                std::to_string(settings.tolerance));
  }
  if (settings.max_iterations < 1) {
    throw std::invalid_argument("CcdSettings.max_iterations: must be >= 1, got " +
                                std::to_string(settings.max_iterations));
  }
  if (!(settings.t_max > 0 && settings.t_max <= 1)) {
    throw std::invalid_argument("CcdSettings.t_max: must be in (0, 1], got " +
                                std::to_string(settings.t_max));
  }
  throw std::logic_error("CcdSettings: throw_out_of_range called with settings in range");
}

}  // namespace stiffsoft::ccd
