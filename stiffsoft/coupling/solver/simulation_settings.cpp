#include <stiffsoft/coupling/solver/simulation_settings.hpp>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>

namespace stiffsoft {

namespace {

[[noreturn]] void fail(const std::string& setting, const std::string& expected, double got) {
  std::ostringstream os;
  os << "SimulationSettings." << setting << ": " << expected << " (got " << got << ")";
  throw std::invalid_argument(os.str());
}

void positive(const std::string& setting, double value) {
  if (!std::isfinite(value) || value <= 0) fail(setting, "must be > 0 and finite", value);
}

void non_negative(const std::string& setting, double value) {
  if (!std::isfinite(value) || value < 0) fail(setting, "must be ≥ 0 and finite", value);
}

}  // namespace

void validate(const SimulationSettings& s) {
  positive("h", s.h);
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(s.gravity[i])) fail("gravity", "must be finite", s.gravity[i]);
  positive("dhat", s.dhat);
  non_negative("mu", s.mu);
  positive("eps_v", s.eps_v);
  if (s.kappa) positive("kappa", *s.kappa);
  positive("tolerance", s.tolerance);
  positive("gap_tolerance", s.gap_tolerance);
  if (!(s.release_hessian > 0 && s.release_hessian <= 1)) fail("release_hessian", "must be in (0, 1]", s.release_hessian);
  if (s.max_iterations < 1) fail("max_iterations", "must be ≥ 1", s.max_iterations);
  if (s.friction_iterations < 1) fail("friction_iterations", "must be ≥ 1", s.friction_iterations);
  try {
    check_linear_solver_name(s.linear_solver);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("SimulationSettings.linear_solver: ") + e.what());
  }
  if (!(s.krylov_rtol_max > 0 && s.krylov_rtol_max < 1))
    fail("krylov_rtol_max", "must be in (0, 1)", s.krylov_rtol_max);
  positive("kinematic_weight", s.kinematic_weight);
  positive("rigidity_bound", s.rigidity_bound);
  non_negative("contact_damping", s.contact_damping);
  for (std::size_t k = 0; k < s.contact_pair_damping.size(); ++k) {
    const ContactPairDamping& p = s.contact_pair_damping[k];
    const std::string at = "contact_pair_damping[" + std::to_string(k) + "]";
    if (p.body_a < 0) fail(at + ".body_a", "must be a body index ≥ 0", p.body_a);
    if (p.body_b < 0) fail(at + ".body_b", "must be a body index ≥ 0", p.body_b);
    non_negative(at + ".damping", p.damping);
  }
  non_negative("sleep_time", s.sleep_time);
  if (s.sleep_speed) positive("sleep_speed", *s.sleep_speed);
}

BarrierSettings barrier_settings(const Model& model, const SimulationSettings& s) {
  BarrierSettings b;
  b.dhat = s.dhat;
  b.kappa = s.kappa;
  b.balance = s.balance_kappa;
  b.hessian = s.barrier_hessian;
  b.release_hessian = s.release_hessian;
  b.bbox_diagonal = model.bounding_box_diagonal();
  double mass = 0;
  int n = 0;
  // Average over what carries DOFs: dynamic affine bodies and dynamic soft nodes (IPC
  // averages over nodes; an affine body is one node of mass m).
  for (const BodyModel& body : model.bodies)
    if (body.dof >= 0 && body.motion == Motion::Dynamic) {
      mass += body.mass;
      ++n;
    }
  for (int i = 0; i < model.nodes.size(); ++i)
    if (model.nodes.motion[i] == Motion::Dynamic) {
      mass += model.nodes.mass[i];
      ++n;
    }
  b.average_mass = n ? mass / n : 1.0;
  return b;
}


}  // namespace stiffsoft
