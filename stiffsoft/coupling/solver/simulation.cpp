#include <stiffsoft/coupling/solver/simulation.hpp>

#include <Eigen/QR>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <stiffsoft/libabd/orthogonality_potential.hpp>
#include <stiffsoft/libfem/format_number.hpp>

namespace stiffsoft {

namespace {
/// Per body: 1 when one of its surface vertices is in an active contact constraint of the
/// barrier's last update, else 0.
std::vector<char> bodies_in_contact(const Model& model, const BarrierTerm& barrier) {
  std::vector<char> touching(model.bodies.size(), 0);
  for (const ContactConstraint& k : barrier.constraints())
    for (int v : k.vertices)
      if (v >= 0) touching[model.mesh.vertex_body[v]] = 1;
  return touching;
}

/// The linear solver of the settings; with linear joint equalities "auto" is CHOLMOD (the
/// reduced system has no DOF blocks for a Krylov backend) and a PETSc backend is an error.
std::string linear_solver_name(const Model& model, const SimulationSettings& s) {
  if (linear_joint_constraints(model).rows() == 0) return s.linear_solver;
  if (s.linear_solver == "auto") return "cholmod";
  if (s.linear_solver.rfind("petsc", 0) == 0)
    throw std::invalid_argument("linear solver \"" + s.linear_solver +
                                "\": scenes with ball, hinge or prismatic joints need a direct solver "
                                "(cholmod or auto); their eliminated equalities leave no DOF blocks for PETSc");
  return s.linear_solver;
}

/// A measured number in an error message, to 4 significant digits.
std::string brief(double value) { return fem::format_significant(value, 4); }

/// The settings, once validate() has accepted them.
const SimulationSettings& validated(const SimulationSettings& settings) {
  validate(settings);
  return settings;
}
}  // namespace

Simulation::Simulation(Model model, const SimulationSettings& settings)
    : m_model(std::move(model)),
      m_settings(validated(settings)),
      m_solver(make_linear_solver(linear_solver_name(m_model, settings))),
      m_hessian(m_model.blocks),
      m_inertia(m_model, settings.kinematic_weight),
      m_orthogonality(m_model, integrator_beta(settings.integrator) * settings.h * settings.h),
      m_elasticity(m_model, integrator_beta(settings.integrator) * settings.h * settings.h),
      m_barrier(m_model, barrier_settings(m_model, settings), &m_times),
      m_constraints(linear_joint_constraints(m_model)),
      m_joints(m_model, integrator_beta(settings.integrator) * settings.h * settings.h),
      m_damping(m_model) {
  if (settings.mu > 0) m_friction.emplace(m_model, settings.mu, settings.eps_v * settings.h);
  m_q = m_model.initial_q();
  if (m_constraints.rows() > 0) {
    const std::vector<double> violation = joint_violations(m_constraints, m_q, int(m_model.joints.size()));
    const double tolerance = 1e-9 * std::max(1.0, m_model.bounding_box_diagonal());
    for (std::size_t j = 0; j < violation.size(); ++j)
      if (violation[j] > tolerance)
        throw std::invalid_argument("joint " + m_model.joints[j].name + ": the initial poses violate it by " +
                                    std::to_string(violation[j]) + " m (expected ≤ " + std::to_string(tolerance) +
                                    " m)");
    m_basis.emplace(m_model, m_constraints);
  }
  m_qdot = m_model.initial_qdot();
  m_q_prev = m_q - settings.h * m_qdot;
  m_qdot_prev = m_qdot;
  m_gravity_q = Eigen::VectorXd::Zero(m_model.num_dofs);
  for (const BodyModel& body : m_model.bodies)
    if (body.dof >= 0 && body.motion == Motion::Dynamic) m_gravity_q.segment<3>(body.dof) = settings.gravity;
  const SoftNodes& nodes = m_model.nodes;
  for (int i = 0; i < nodes.size(); ++i)
    if (nodes.motion[i] == Motion::Dynamic) m_gravity_q.segment<3>(nodes.dof[i]) = settings.gravity;
  for (const BodyModel& body : m_model.bodies)
    if (body.block >= 0 && body.motion == Motion::Kinematic) m_prescribed_blocks.push_back(body.block);
  for (int i = 0; i < nodes.size(); ++i)
    if (nodes.motion[i] == Motion::Kinematic) m_prescribed_blocks.push_back(nodes.block[i]);
  if (settings.sleep_time > 0)
    m_sleeping.emplace(m_model, settings.sleep_time, settings.sleep_speed.value_or(settings.tolerance));
}

StepStats Simulation::step() {
  m_slept = m_sleeping && m_sleeping->all_asleep();
  if (m_slept) return sleeping_step();
  const auto start = std::chrono::steady_clock::now();
  m_times = PhaseTimes{};
  const double h = m_settings.h;
  Eigen::VectorXd q_tilde =
      predicted_q(m_settings.integrator, h, m_q, m_qdot, m_q_prev, m_qdot_prev, m_gravity_q);
  for (int b = 0; b < int(m_model.bodies.size()); ++b)
    if (m_model.bodies[b].dof >= 0 && m_model.bodies[b].motion == Motion::Kinematic)
      q_tilde.segment<12>(m_model.bodies[b].dof) = m_model.kinematic_q(b, m_time + h);
  const SoftNodes& nodes = m_model.nodes;
  for (int i = 0; i < nodes.size(); ++i)
    if (nodes.motion[i] == Motion::Kinematic)
      q_tilde.segment<3>(nodes.dof[i]) = (nodes.X.row(i) + (m_time + h) * nodes.velocity.row(i)).transpose();
  const Eigen::MatrixX3d x_n = m_model.surface(m_q);
  const Configuration c_n{m_q, x_n};
  const double kappa_n = m_barrier.kappa();
  const bool balanced_n = m_barrier.kappa_balanced();
  const LinearSolverMemory memory_n = m_sleeping ? m_solver->memory() : LinearSolverMemory{};
  StepStats stats;
  std::vector<EnergyTerm*> terms;
  std::vector<int> held;
  // Solved again from the start while a moving body meets a sleeping one, which then wakes: no
  // accepted step holds a body that a moving one came within d̂ of.
  Eigen::VectorXd q_new = solve_step(q_tilde, c_n, stats, terms, held);
  Eigen::MatrixX3d x = m_model.surface(q_new);
  while (m_sleeping && !m_sleeping->wake_met_by_moves(x_n, x, m_settings.dhat, h).empty()) {
    m_barrier.restore_stiffness(kappa_n, balanced_n);
    m_solver->restore_memory(memory_n);
    q_new = solve_step(q_tilde, c_n, stats, terms, held);
    x = m_model.surface(q_new);
  }
  check_rigidity(q_new);

  Eigen::VectorXd qdot_new = updated_qdot(m_settings.integrator, h, q_new, m_q, m_q_prev);
  for (int b : held) qdot_new.segment(m_model.blocks[b].offset, m_model.blocks[b].size).setZero();
  m_q_prev = m_q;
  m_qdot_prev = m_qdot;
  m_q = q_new;
  m_qdot = qdot_new;
  m_time += h;
  ++m_step;

  if (m_sleeping) {
    m_barrier.update({m_q, x});
    for (int b : m_sleeping->end_step(m_barrier.constraints(), m_model.surface_step(m_qdot), h)) {
      const BodyModel& body = m_model.bodies[b];
      m_qdot.segment<12>(body.dof).setZero();
      m_qdot_prev.segment<12>(body.dof).setZero();
      m_q_prev.segment<12>(body.dof) = m_q.segment<12>(body.dof);
    }
  }
  if (m_friction) {
    const FrictionTerm::StickSlip stick_slip = m_friction->stick_slip({m_q, x});
    stats.sticking = stick_slip.sticking;
    stats.sliding = stick_slip.sliding;
    stats.stick_slip_flips = m_friction->stick_slip_flips();
  }
  if (!m_model.joints.empty()) {
    for (EnergyTerm* t : terms) t->update({m_q, x});
    compute_joint_forces(terms, {m_q, x});
    for (const Eigen::Vector3d& f : m_joint_forces) stats.joint_force = std::max(stats.joint_force, f.norm());
  }
  finish_stats(stats, x, start);
  return stats;
}

Eigen::VectorXd Simulation::solve_step(const Eigen::VectorXd& q_tilde, const Configuration& c_n, StepStats& stats,
                                       std::vector<EnergyTerm*>& terms, std::vector<int>& held) {
  const double h = m_settings.h;
  // A sleeping body's target is where it is (held there, it has no other).
  const auto still_target = [&] {
    Eigen::VectorXd target = q_tilde;
    if (m_sleeping) copy_blocks(m_sleeping->held_blocks(), m_q, target);
    return target;
  };
  m_inertia.set_target(still_target());

  // Lag friction and balance κ at the start-of-step configuration.
  if (m_sleeping) m_barrier.hold_still(m_sleeping->still_bodies());
  m_barrier.update(c_n);
  Eigen::VectorXd q_new = initial_guess(q_tilde, c_n);
  if (m_sleeping && !m_sleeping->wake_near_moves(c_n.x, m_model.surface(q_new), m_settings.dhat, h).empty()) {
    m_inertia.set_target(still_target());
    m_barrier.hold_still(m_sleeping->still_bodies());  // the woken bodies' contacts back
    m_barrier.update(c_n);
  }
  // Only the terms the scene needs: no orthogonality without affine bodies, no elasticity
  // without soft ones, no friction with μ = 0.
  terms = {&m_inertia};
  if (!m_orthogonality.empty()) terms.push_back(&m_orthogonality);
  if (!m_elasticity.empty()) terms.push_back(&m_elasticity);
  Eigen::VectorXd grad_other = Eigen::VectorXd::Zero(m_q.size());
  for (const EnergyTerm* t : terms) t->add_gradient(c_n, grad_other);
  m_barrier.initialize_stiffness(c_n, grad_other);
  terms.push_back(&m_barrier);
  if (m_friction) {
    m_friction->lag(c_n, m_barrier);
    terms.push_back(&*m_friction);
  }
  if (!m_joints.empty()) terms.push_back(&m_joints);
  const double beta = integrator_beta(m_settings.integrator);
  m_damping.start_step(m_q, beta * h);
  m_damping.lag_contact(c_n, m_barrier, m_settings.contact_damping, m_settings.contact_pair_damping, beta * h * h);
  m_damping.lag_joints();
  if (!m_damping.empty()) terms.push_back(&m_damping);

  NewtonSettings ns;
  ns.tolerance = m_settings.tolerance;
  ns.gap_tolerance = m_settings.gap_tolerance;
  if (m_friction && m_settings.friction_iterations > 1) ns.stick_tolerance = friction_resolution;
  ns.h = h;
  ns.potential_scale = beta * h * h;
  ns.max_iterations = m_settings.max_iterations;
  ns.geodesic_line_search = m_settings.geodesic_line_search;
  ns.island_line_search = m_settings.island_line_search;
  ns.entering_springs = m_settings.entering_springs;
  ns.forcing.eta_max = m_settings.krylov_rtol_max;
  ns.observer = m_newton_observer;
  if (m_sleeping) ns.held_blocks = m_sleeping->held_blocks();
  const auto minimize = [&] {
    return m_prescribed_blocks.empty()
               ? newton_minimize(m_model, terms, q_new, *m_solver, ns, m_times, reduced_basis(), &m_hessian)
               : follow_paths(terms, q_tilde, ns, q_new);
  };
  accumulate(stats.newton, minimize());
  // Friction lagged at qⁿ misses a contact that starts within the step (a landing slides on
  // without friction for a step): lag again at the result while that changes some body's
  // velocity by more than friction_resolution ε_v, up to contact.friction_iterations lags in all.
  for (int lags = 1; m_friction; ++lags) {
    const Configuration c{q_new, m_model.surface(q_new)};
    m_barrier.update(c);
    stats.friction_lag_error = friction_lag_error(c);
    if (lags == m_settings.friction_iterations || !stats.newton.converged ||
        !(stats.friction_lag_error > friction_resolution * m_settings.eps_v))
      break;
    m_friction->relag(c, m_barrier);
    ++stats.friction_relags;
    accumulate(stats.newton, minimize());
  }
  if (m_basis) q_new = m_basis->project(q_new);  // removes round-off drift along the equalities
  copy_blocks(ns.held_blocks, m_q, q_new);      // exactly where they were, whatever the line search's round-off
  held = ns.held_blocks;
  return q_new;
}

StepStats Simulation::sleeping_step() {
  const auto start = std::chrono::steady_clock::now();
  m_times = PhaseTimes{};
  m_q_prev = m_q;
  m_qdot_prev = m_qdot;
  m_time += m_settings.h;
  ++m_step;
  StepStats stats;
  stats.newton.converged = true;
  const Eigen::MatrixX3d x = m_model.surface(m_q);
  m_barrier.hold_still(m_sleeping->still_bodies());  // the same after a restore
  m_barrier.update({m_q, x});                         // the contacts stats reports (already built but after a restore)
  finish_stats(stats, x, start);
  return stats;
}

void Simulation::copy_blocks(const std::vector<int>& blocks, const Eigen::VectorXd& from, Eigen::VectorXd& v) const {
  for (int b : blocks) {
    const DofBlock& block = m_model.blocks[b];
    v.segment(block.offset, block.size) = from.segment(block.offset, block.size);
  }
}

void Simulation::finish_stats(StepStats& stats, const Eigen::MatrixX3d& x, std::chrono::steady_clock::time_point start) {
  stats.step = m_step;
  stats.time = m_time;
  stats.contacts = int(m_barrier.constraints().size());
  stats.smallest_distance = m_barrier.min_active_distance({m_q, x});
  stats.kappa = m_barrier.kappa();
  for (double v : joint_violations(m_constraints, m_q, int(m_model.joints.size())))
    stats.joint_error = std::max(stats.joint_error, v);
  const SoftNodes& nodes = m_model.nodes;
  for (int i = 0; i < nodes.size(); ++i) {
    if (nodes.motion[i] != Motion::Dynamic) continue;
    const Eigen::Vector3d v = m_qdot.segment<3>(nodes.dof[i]);
    stats.kinetic_energy += 0.5 * nodes.mass[i] * v.squaredNorm();
    stats.potential_energy -= nodes.mass[i] * m_settings.gravity.dot(m_q.segment<3>(nodes.dof[i]));
    stats.linear_momentum += nodes.mass[i] * v;
  }
  for (const BodyModel& body : m_model.bodies) {
    if (body.dof < 0 || body.motion != Motion::Dynamic) continue;
    const abd::Vector12d qd = m_qdot.segment<12>(body.dof);
    stats.kinetic_energy += 0.5 * qd.dot(body.M * qd);
    stats.potential_energy -= body.mass * m_settings.gravity.dot(m_q.segment<3>(body.dof));
    stats.linear_momentum += body.mass * qd.head<3>();
    stats.orthogonality_error =
        std::max(stats.orthogonality_error, abd::orthogonality_error(m_q.segment<12>(body.dof)));
  }
  if (!m_elasticity.empty()) {
    stats.elastic_energy = m_elasticity.value({m_q, x}) /
                           (integrator_beta(m_settings.integrator) * m_settings.h * m_settings.h);
    stats.inverted_per_body = m_elasticity.inverted_per_body(m_q);
    stats.inverted_tets = std::accumulate(stats.inverted_per_body.begin(), stats.inverted_per_body.end(), 0);
  }
  if (m_sleeping) stats.sleeping_bodies = m_sleeping->sleeping_count();
  stats.times = m_times;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double Simulation::friction_lag_error(const Configuration& c) {
  const std::vector<double> lagged = m_friction->normal_force_per_body();
  const std::vector<double> now = m_friction->normal_force_per_body(c, m_barrier);
  // λ is in the incremental potential's units (force × β h²): a change μ Δλ of the friction
  // moves the step's result by δq = μ Δλ / m, and its velocity by c δq / h.
  const double h_over_c = m_settings.h / velocity_coefficient(m_settings.integrator);
  double worst = 0;
  for (std::size_t b = 0; b < m_model.bodies.size(); ++b) {
    const BodyModel& body = m_model.bodies[b];
    if (body.motion != Motion::Dynamic || !(body.mass > 0)) continue;
    worst = std::max(worst, m_settings.mu * std::abs(now[b] - lagged[b]) / (h_over_c * body.mass));
  }
  return worst;
}

SimulationState Simulation::state() const {
  return {m_time,
          m_step,
          m_q,
          m_qdot,
          m_q_prev,
          m_qdot_prev,
          m_barrier.kappa(),
          m_barrier.kappa_balanced(),
          m_solver->memory(),
          m_sleeping ? m_sleeping->state() : Sleeping::State{}};
}

void Simulation::restore(const SimulationState& s) {
  const Eigen::Index n = m_q.size();
  if (s.q.size() != n || s.qdot.size() != n || s.q_prev.size() != n || s.qdot_prev.size() != n)
    throw std::invalid_argument("Simulation::restore: the state has " + std::to_string(s.q.size()) +
                                " DOFs, this model " + std::to_string(n));
  m_time = s.time;
  m_step = s.step;
  m_q = s.q;
  m_qdot = s.qdot;
  m_q_prev = s.q_prev;
  m_qdot_prev = s.qdot_prev;
  m_barrier.restore_stiffness(s.kappa, s.kappa_balanced);
  m_solver->restore_memory(s.solver);
  if (m_sleeping) m_sleeping->restore(s.sleeping);
}

Eigen::VectorXd Simulation::initial_guess(const Eigen::VectorXd& q_tilde, const Configuration& c_n) const {
  Eigen::VectorXd q_start = q_tilde;
  // A body that touches something at qⁿ starts without q̃'s β h² g: what it rests on holds it
  // there, and the free-fall term would press it into the barrier first, out of which Newton
  // climbs only slowly (on a log barrier, an iterate too close about doubles its gap per
  // iteration). The energy still has q̃; only where Newton starts changes.
  const double beta_h2 = integrator_beta(m_settings.integrator) * m_settings.h * m_settings.h;
  const std::vector<char> touching = bodies_in_contact(m_model, m_barrier);
  const SoftNodes& nodes = m_model.nodes;
  for (int b = 0; b < int(m_model.bodies.size()); ++b) {
    if (!touching[b]) continue;
    const BodyModel& body = m_model.bodies[b];
    if (body.dof >= 0) q_start.segment<3>(body.dof) -= beta_h2 * m_gravity_q.segment<3>(body.dof);
    for (int i = body.node_begin; i < body.node_end; ++i)
      if (nodes.dof[i] >= 0) q_start.segment<3>(nodes.dof[i]) -= beta_h2 * m_gravity_q.segment<3>(nodes.dof[i]);
  }
  for (const BodyModel& body : m_model.bodies) {
    if (body.dof < 0 || body.motion != Motion::Dynamic) continue;
    const abd::Vector12d qb = m_q.segment<12>(body.dof);
    const Eigen::Vector3d omega = abd::angular_velocity(qb, m_qdot.segment<12>(body.dof));
    q_start.segment<9>(body.dof + 3) = abd::rigid_motion(qb, Eigen::Vector3d::Zero(), omega, m_settings.h).tail<9>();
  }
  if (m_sleeping) copy_blocks(m_sleeping->held_blocks(), m_q, q_start);
  // Joints: onto their linear equalities (qⁿ satisfies them, so the whole segment does), and
  // not across a joint limit.
  if (m_basis) q_start = m_basis->project(q_start);
  const Eigen::VectorXd dq = q_start - m_q;
  const Eigen::MatrixX3d dx = m_model.surface_step(dq);
  double alpha = m_barrier.max_step(c_n, dq, dx);
  if (!m_joints.empty()) alpha = std::min(alpha, m_joints.max_step(c_n, alpha * dq, alpha * dx) * alpha);
  return m_q + alpha * dq;
}

NewtonReport Simulation::follow_paths(const std::vector<EnergyTerm*>& terms, const Eigen::VectorXd& q_tilde,
                                      const NewtonSettings& ns, Eigen::VectorXd& q) {
  NewtonSettings held = ns;  // the sleeping bodies' blocks, and the prescribed ones
  held.held_blocks.insert(held.held_blocks.end(), m_prescribed_blocks.begin(), m_prescribed_blocks.end());
  if (!m_basis) {
    // The initial guess reached the path (to the round-off of qⁿ + 1·(q̃ − qⁿ)), or the
    // prescribed blocks alone can move there from qⁿ.
    if (path_lag(q, q_tilde).first <= 1e-12 * std::max(1.0, m_model.bounding_box_diagonal())) {
      q = on_path(q, q_tilde);
      return newton_minimize(m_model, terms, q, *m_solver, held, m_times, nullptr, &m_hessian);
    }
    const Eigen::VectorXd q_on = on_path(m_q, q_tilde);
    if (moves_freely(m_q, q_on)) {
      q = q_on;
      return newton_minimize(m_model, terms, q, *m_solver, held, m_times, nullptr, &m_hessian);
    }
  }
  // Something sits on the path: push it out of the way with a stiff pull, then hold.
  constexpr int kPullRounds = 5;  // weights w, 10 w, …, 10⁴ w
  NewtonReport report;
  double weight = m_settings.kinematic_weight;
  for (int round = 0;; ++round, weight *= 10) {
    m_inertia.set_kinematic_weight(weight);
    accumulate(report,
               newton_minimize(m_model, terms, q, *m_solver, ns, m_times, reduced_basis(), &m_hessian));
    const bool there = m_basis ? path_lag(q, q_tilde).first <= ns.tolerance * ns.h
                               : moves_freely(q, on_path(q, q_tilde));
    if (there) break;
    if (round + 1 == kPullRounds) {
      m_inertia.set_kinematic_weight(m_settings.kinematic_weight);
      throw path_blocked(q, q_tilde);
    }
  }
  m_inertia.set_kinematic_weight(m_settings.kinematic_weight);
  if (m_basis) return report;
  q = on_path(q, q_tilde);
  accumulate(report, newton_minimize(m_model, terms, q, *m_solver, held, m_times, nullptr, &m_hessian));
  return report;
}

Eigen::VectorXd Simulation::on_path(const Eigen::VectorXd& q, const Eigen::VectorXd& q_tilde) const {
  Eigen::VectorXd q_on = q;
  for (int b : m_prescribed_blocks) {
    const DofBlock& block = m_model.blocks[b];
    q_on.segment(block.offset, block.size) = q_tilde.segment(block.offset, block.size);
  }
  return q_on;
}

bool Simulation::moves_freely(const Eigen::VectorXd& from, const Eigen::VectorXd& to) const {
  const Eigen::VectorXd dq = to - from;
  const Eigen::MatrixX3d dx = m_model.surface_step(dq);
  const Configuration c{from, m_model.surface(from)};
  if (m_barrier.max_step(c, dq, dx) < 1) return false;
  return m_joints.empty() || m_joints.max_step(c, dq, dx) >= 1;
}

std::pair<double, int> Simulation::path_lag(const Eigen::VectorXd& q, const Eigen::VectorXd& q_tilde) const {
  const Eigen::VectorXd dq = on_path(q, q_tilde) - q;
  const Eigen::MatrixX3d dx = m_model.surface_step(dq);
  std::pair<double, int> lag{0.0, -1};
  const auto farther = [&](double d, int body) {
    if (d > lag.first) lag = {d, body};
  };
  for (int v = 0; v < dx.rows(); ++v) farther(dx.row(v).norm(), m_model.mesh.vertex_body[v]);
  const SoftNodes& nodes = m_model.nodes;
  for (int i = 0; i < nodes.size(); ++i)
    if (nodes.motion[i] == Motion::Kinematic) farther(dq.segment<3>(nodes.dof[i]).norm(), nodes.body[i]);
  return lag;
}

PhysicsError Simulation::path_blocked(const Eigen::VectorXd& q, const Eigen::VectorXd& q_tilde) const {
  const auto [lag, body] = path_lag(q, q_tilde);
  const BodyModel& b = m_model.bodies[std::max(body, 0)];
  // The bodies in contact with it, from the barrier's active set at q.
  std::vector<std::string> touching;
  for (const ContactConstraint& contact : m_barrier.constraints()) {
    bool involved = false;
    for (int v : contact.vertices) involved = involved || (v >= 0 && m_model.mesh.vertex_body[v] == body);
    if (!involved) continue;
    for (int v : contact.vertices) {
      if (v < 0 || m_model.mesh.vertex_body[v] == body) continue;
      const std::string& name = m_model.bodies[m_model.mesh.vertex_body[v]].name;
      if (std::find(touching.begin(), touching.end(), name) == touching.end()) touching.push_back(name);
    }
  }
  std::string against;
  for (const std::string& name : touching) against += (against.empty() ? "'" : ", '") + name + "'";
  const std::string what = b.motion == Motion::Kinematic ? "kinematic body '" + b.name + "'"
                                                         : "the prescribed nodes of soft body '" + b.name + "'";
  return PhysicsError(what + " cannot follow its path at step " + std::to_string(m_step + 1) + " (t = " +
                      brief(m_time + m_settings.h) + " s): contact" +
                      (against.empty() ? "" : " with " + against) + " holds it " + brief(lag) +
                      " m short, even under a pull " + brief(m_settings.kinematic_weight * 1e4) +
                      " times its own inertia. Something is caught between it and a fixed or kinematic body and would "
                      "have to intersect; change the path, or make room");
}

void Simulation::check_rigidity(const Eigen::VectorXd& q) const {
  for (const BodyModel& body : m_model.bodies) {
    if (body.dof < 0 || body.motion != Motion::Dynamic) continue;
    const double error = abd::orthogonality_error(q.segment<12>(body.dof));
    if (error <= m_settings.rigidity_bound) continue;
    throw PhysicsError("affine body '" + body.name + "': rigidity error ‖AᵀA − I‖ = " + brief(error) +
                       " at step " + std::to_string(m_step + 1) + " (t = " + brief(m_time + m_settings.h) +
                       " s) exceeds the bound " + brief(m_settings.rigidity_bound) +
                       ": contact or joint forces beyond what its orthogonality stiffness κ can hold. Raise the "
                       "body's `kappa`, lower `dt`, or fix an impossible setup (a body crushed between others); "
                       "the bound is `solver/rigidity_bound`");
  }
}

void Simulation::compute_joint_forces(const std::vector<EnergyTerm*>& terms, const Configuration& c) {
  const int joints = int(m_model.joints.size());
  m_joint_forces.assign(joints, Eigen::Vector3d::Zero());
  const double beta_h2 = integrator_beta(m_settings.integrator) * m_settings.h * m_settings.h;
  if (m_constraints.rows() > 0) {
    // ∇E = Cᵀ μ over the columns C touches, in the least-squares sense (redundant rows share).
    Eigen::VectorXd g = Eigen::VectorXd::Zero(m_q.size());
    for (const EnergyTerm* t : terms) t->add_gradient(c, g);
    std::vector<int> columns;
    for (int col = 0; col < m_constraints.C.outerSize(); ++col)
      if (m_constraints.C.col(col).nonZeros() > 0) columns.push_back(col);
    Eigen::MatrixXd Ct(columns.size(), m_constraints.rows());
    Eigen::VectorXd g_t(columns.size());
    for (std::size_t j = 0; j < columns.size(); ++j) {
      Ct.row(j) = Eigen::RowVectorXd(m_constraints.C.col(columns[j]).transpose());
      g_t[j] = g[columns[j]];
    }
    const Eigen::VectorXd mu = Ct.completeOrthogonalDecomposition().solve(g_t);
    for (int i = 0; i + 2 < m_constraints.rows(); i += 3)
      if (m_constraints.row_is_point[i]) m_joint_forces[m_constraints.row_joint[i]] += mu.segment<3>(i) / beta_h2;
  }
  for (const auto& [p, v] : m_joints.potentials()) {
    if (measure_is_angle(p.measure)) continue;  // a torque, not reported
    const Eigen::VectorXd y = v.gather(c.q);
    if (p.inactive(measure(p.measure, y))) continue;
    const MeasureValue m = measure_derivatives(p.measure, y);
    m_joint_forces[p.joint] -= p.first_derivative(m.s) * m.grad.head<3>();
  }
}

std::vector<Eigen::Vector3d> Simulation::joint_positions() const {
  std::vector<Eigen::Vector3d> x;
  for (const JointModel& joint : m_model.joints) x.push_back(end_point(m_model, joint.a, joint.a.anchor).value(m_q));
  return x;
}

std::vector<Eigen::Vector3d> Simulation::joint_positions_b() const {
  std::vector<Eigen::Vector3d> x;
  for (const JointModel& joint : m_model.joints) x.push_back(end_point(m_model, joint.b, joint.b.anchor).value(m_q));
  return x;
}

std::vector<double> Simulation::joint_gaps() const {
  std::vector<double> gaps(m_model.joints.size(), std::numeric_limits<double>::quiet_NaN());
  for (const auto& [p, v] : m_joints.potentials()) {
    if (p.wrap != JointWrap::LowerBarrier && p.wrap != JointWrap::UpperBarrier) continue;
    const double g = p.gap(measure(p.measure, v.gather(m_q)));
    if (std::isnan(gaps[p.joint]) || g < gaps[p.joint]) gaps[p.joint] = g;
  }
  return gaps;
}

Eigen::MatrixX3d Simulation::contact_forces() const {
  const Eigen::MatrixX3d x = m_model.surface(m_q);
  const double scale = integrator_beta(m_settings.integrator) * m_settings.h * m_settings.h;
  return m_barrier.vertex_forces({m_q, x}) / scale;
}

Eigen::MatrixX3d Simulation::friction_forces() const {
  const Eigen::MatrixX3d x = m_model.surface(m_q);
  if (!m_friction || m_slept) return Eigen::MatrixX3d::Zero(x.rows(), 3);
  const double scale = integrator_beta(m_settings.integrator) * m_settings.h * m_settings.h;
  return m_friction->vertex_forces({m_q, x}) / scale;
}

}  // namespace stiffsoft

namespace stiffsoft {

Eigen::MatrixX3d Simulation::node_velocities() const {
  const SoftNodes& nodes = m_model.nodes;
  Eigen::MatrixX3d v = Eigen::MatrixX3d::Zero(nodes.size(), 3);
  for (int i = 0; i < nodes.size(); ++i)
    if (nodes.dof[i] >= 0) v.row(i) = m_qdot.segment<3>(nodes.dof[i]).transpose();
  return v;
}

Eigen::VectorXd Simulation::von_mises() const { return m_elasticity.von_mises(m_q); }

}  // namespace stiffsoft
