#pragma once
/// @file Lamé parameters from engineering constants, with the range checks every material uses.

namespace stiffsoft::fem {

/// Lamé parameters of small-strain isotropic elasticity (Pa).
struct LameParameters {
  double mu = 0;      ///< shear modulus μ = E / (2(1 + ν)) (Pa)
  double lambda = 0;  ///< first Lamé parameter λ = E ν / ((1 + ν)(1 − 2ν)) (Pa)
};

/// μ and λ from Young's modulus E (Pa) and Poisson ratio ν.
/// @pre E > 0 and −1 < ν < 0.5; otherwise throws std::invalid_argument naming the value.
LameParameters lame_parameters(double youngs_modulus, double poisson_ratio);

/// Throws std::invalid_argument unless E > 0 (Pa) is finite.
void check_youngs_modulus(double youngs_modulus);

/// Throws std::invalid_argument unless −1 < ν < 0.5.
void check_poisson_ratio(double poisson_ratio);

/// Throws std::invalid_argument unless ρ > 0 (kg/m³) is finite.
void check_density(double density);

}  // namespace stiffsoft::fem
