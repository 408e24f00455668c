#include <stiffsoft/scene/model_choice.hpp>

#include <algorithm>
#include <cmath>

namespace stiffsoft {

double estimated_strain(const SceneLoads& loads, double volume, double density, double young) {
  const double area = std::pow(volume, 2.0 / 3.0);
  const double static_strain = loads.weight / (area * young);
  const double impact_strain = loads.fastest_speed * std::sqrt(density / young);
  return std::max(static_strain, impact_strain);
}

}  // namespace stiffsoft
