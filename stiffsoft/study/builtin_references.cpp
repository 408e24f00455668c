#include <stiffsoft/study/builtin_references.hpp>

namespace stiffsoft::study {

const std::vector<BuiltinReference>& builtin_references() {
  static const std::vector<BuiltinReference> references{
      {"incline_sliding_distance",
       {"0.5 * g * (sin(theta) - mu * cos(theta)) * t^2"},
       {"g", "theta", "mu"},
       "distance (m) slid from rest down an incline of angle theta (rad) with Coulomb friction mu < tan(theta)"},
      {"free_fall_drop",
       {"-0.5 * g * t^2"},
       {"g"},
       "vertical displacement (m) of a body falling from rest"},
      {"steady_rotation_z",
       {"cos(omega * t)", "-sin(omega * t)", "0", "sin(omega * t)", "cos(omega * t)", "0", "0", "0", "1"},
       {"omega"},
       "rotation matrix (row-major) of a body spinning at omega (rad/s) about the world z axis, starting unrotated"},
      {"cantilever_tip_self_weight",
       {"-rho * g * b * hb * L^4 / (8 * E * b * hb^3 / 12)"},
       {"rho", "g", "b", "hb", "L", "E"},
       "Euler-Bernoulli tip deflection (m, downward negative) of a cantilever of length L, width b, height hb under its own weight"},
      {"hertz_force",
       {"4 / 3 * E / (1 - nu^2) * sqrt(R) * delta^1.5"},
       {"E", "nu", "R", "delta"},
       "Hertz force (N) of an elastic sphere of radius R pressed by delta on a rigid plane"},
      {"intermediate_axis_growth_rate",
       {"Omega * sqrt((I2 - I1) * (I3 - I2) / (I1 * I3))"},
       {"Omega", "I1", "I2", "I3"},
       "growth rate (1/s) of a perturbation of a spin Omega about the intermediate axis"},
  };
  return references;
}

const BuiltinReference* find_builtin_reference(const std::string& name) {
  for (const BuiltinReference& r : builtin_references())
    if (r.name == name) return &r;
  return nullptr;
}

}  // namespace stiffsoft::study
