#include <stiffsoft/libfem/make_material.hpp>

#include <stdexcept>
#include <string>

#include <stiffsoft/libfem/fixed_corotated.hpp>
#include <stiffsoft/libfem/linear_elasticity.hpp>
#include <stiffsoft/libfem/stable_neo_hookean.hpp>

namespace stiffsoft::fem {

std::unique_ptr<Material> make_material(std::string_view name, double E, double nu) {
  if (name == "linear") return std::make_unique<LinearElasticity>(E, nu);
  if (name == "fixed_corotated") return std::make_unique<FixedCorotated>(E, nu);
  if (name == "stable_neo_hookean") return std::make_unique<StableNeoHookean>(E, nu);
  throw std::invalid_argument("libfem: unknown material model \"" + std::string(name) +
                              "\"; expected one of \"linear\", \"fixed_corotated\", "
                              "\"stable_neo_hookean\"");
}

}  // namespace stiffsoft::fem
