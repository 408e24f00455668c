#pragma once
/// @file The material factory: a model by name, as scene files spell it.

#include <memory>
#include <string_view>

#include <stiffsoft/libfem/material.hpp>

namespace stiffsoft::fem {

/// The material `name` ∈ {"linear", "fixed_corotated", "stable_neo_hookean"} with Young's modulus
/// E (Pa) and Poisson ratio ν. Throws std::invalid_argument for an unknown name (listing the valid
/// ones) or for E ≤ 0, ν ∉ (−1, 0.5).
std::unique_ptr<Material> make_material(std::string_view name, double youngs_modulus, double poisson_ratio);

}  // namespace stiffsoft::fem
