#include "peers/stiffsoft_engine.hpp"

#include <algorithm>
#include <cstdio>

#include <stiffsoft/libabd/affine_body.hpp>

namespace stiffsoft::peers {

SimulationSettings coarse_settings(const PeerScene& scene) {
  SimulationSettings s = scene.settings;
  const double L = scene.model.bounding_box_diagonal();
  s.eps_v = std::max(s.eps_v, 1e-2 * L);
  s.tolerance = std::max(s.tolerance, 5e-2 * L);
  return s;
}

StiffsoftEngine::StiffsoftEngine(const PeerScene& scene, const SimulationSettings& settings, std::string name)
    : m_simulation(scene.model, settings), m_name(std::move(name)) {}

std::string StiffsoftEngine::settings() const {
  const SimulationSettings& s = m_simulation.settings();
  char line[512];
  std::snprintf(line, sizeof line,
                "%s, d^ = %.3g m, mu = %.3g, eps_v = %.3g m/s, kappa %s, Newton tol. %.3g m/s, max %d it., %s",
                s.integrator == Integrator::BackwardEuler ? "backward Euler" : "BDF-2", s.dhat, s.mu, s.eps_v,
                s.kappa ? "fixed" : "adaptive", s.tolerance, s.max_iterations, s.linear_solver.c_str());
  std::string text = line;
  if (s.sleep_time > 0) {
    std::snprintf(line, sizeof line, ", bodies sleep after %.3g s below %.3g m/s", s.sleep_time,
                  s.sleep_speed.value_or(s.tolerance));
    text += line;
  }
  return text;
}

void StiffsoftEngine::step() {
  const StepStats stats = m_simulation.step();
  m_details.newton_iterations = stats.newton.iterations;
  m_details.converged = stats.newton.converged;
  m_details.smallest_distance = stats.smallest_distance;
  m_details.broad_phase_s = stats.times.broad_phase;
  m_details.ccd_s = stats.times.ccd;
  m_details.assembly_s = stats.times.assembly;
  m_details.solve_s = stats.times.solve;
}

Pose StiffsoftEngine::pose(int b) const {
  const abd::Vector12d q = m_simulation.model().body_q(b, m_simulation.q());
  return {abd::affine_matrix(q), abd::translation(q)};
}

Eigen::MatrixX3d StiffsoftEngine::collision_vertices(int b) const {
  const BodyModel& body = m_simulation.model().bodies[b];
  return m_simulation.surface().middleRows(body.vertex_begin, body.vertex_end - body.vertex_begin);
}

Twist StiffsoftEngine::twist(int b) const {
  const BodyModel& body = m_simulation.model().bodies[b];
  if (body.dof < 0) return {};
  const abd::Vector12d q = m_simulation.q().segment<12>(body.dof), qdot = m_simulation.qdot().segment<12>(body.dof);
  return {qdot.head<3>(), abd::angular_velocity(q, qdot)};
}

}  // namespace stiffsoft::peers
