#include <stiffsoft/libfem/lame_parameters.hpp>

#include <cmath>
#include <stdexcept>

#include <stiffsoft/libfem/format_number.hpp>

namespace stiffsoft::fem {

void check_youngs_modulus(double E) {
  if (!(E > 0) || !std::isfinite(E))
    throw std::invalid_argument("libfem: Young's modulus E = " + format_number(E) +
                                " Pa is invalid; expected a finite E > 0");
}

void check_poisson_ratio(double nu) {
  // ν → 0.5 makes λ infinite (incompressible), ν → −1 makes μ infinite.
  if (!(nu > -1 && nu < 0.5))
    throw std::invalid_argument("libfem: Poisson ratio nu = " + format_number(nu) +
                                " is invalid; expected -1 < nu < 0.5");
}

void check_density(double rho) {
  if (!(rho > 0) || !std::isfinite(rho))
    throw std::invalid_argument("libfem: density rho = " + format_number(rho) +
                                " kg/m^3 is invalid; expected a finite rho > 0");
}

LameParameters lame_parameters(double E, double nu) {
  check_youngs_modulus(E);
  check_poisson_ratio(nu);
  return {E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))};
}

}  // namespace stiffsoft::fem
