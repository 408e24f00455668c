#pragma once
/// @file `model: "auto"`: affine when a body is stiff enough for the scene's loads.
///
/// The strain a body sees is estimated from two loads, and the larger wins:
/// - static: the weight of every dynamic body of the scene resting on this one's cross-section,
///   ε_static = W / (A E), W = Σ_dynamic ρ_b V_b |g|, A = V^{2/3};
/// - impact: a 1-D elastic impact at the fastest speed a body can reach, ε_impact = v / c,
///   c = √(E/ρ) the bar wave speed, v = max_b |v_b| + √(2 |g| H), H the scene's height
///   along gravity.
/// The body is affine when ε = max(ε_static, ε_impact) < 1e-3 (rigid to within 0.1 %, the
/// accuracy an affine body's orthogonality potential already trades), soft otherwise.

#include <string>

namespace stiffsoft {

/// The strain below which `auto` bodies become affine.
inline constexpr double kAutoAffineStrain = 1e-3;

/// The loads of a scene that decide `auto` bodies.
struct SceneLoads {
  double weight = 0;        ///< W: total weight of the dynamic bodies (N)
  double fastest_speed = 0; ///< v: largest initial speed plus the fall from the scene's height (m/s)
};

/// The estimated strain ε of a body of volume V (m³), density ρ (kg/m³) and Young's modulus E
/// (Pa) under the scene's loads.
double estimated_strain(const SceneLoads& loads, double volume, double density, double young);

/// True when a body with this estimated strain is made affine.
inline bool auto_is_affine(double strain) { return strain < kAutoAffineStrain; }

}  // namespace stiffsoft
