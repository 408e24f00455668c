#include <stiffsoft/coupling/solver/sleeping.hpp>

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include <stiffsoft/coupling/contact/broad_phase.hpp>
#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

namespace {

/// Body b's box over the rows of x, grown by r on every side.
AxisBox body_box(const BodyModel& body, const Eigen::MatrixX3d& x, double r) {
  AxisBox box(Eigen::Array3d::Constant(std::numeric_limits<double>::infinity()),
              Eigen::Array3d::Constant(-std::numeric_limits<double>::infinity()));
  for (int v = body.vertex_begin; v < body.vertex_end; ++v) {
    box.lo = box.lo.min(x.row(v).transpose().array());
    box.hi = box.hi.max(x.row(v).transpose().array());
  }
  box.lo -= r;
  box.hi += r;
  return box;
}

/// Whether body b may sleep: a dynamic affine body.
bool may_sleep(const BodyModel& body) {
  return body.representation == Representation::Affine && body.motion == Motion::Dynamic && body.dof >= 0;
}

}  // namespace

Sleeping::Sleeping(const Model& model, double time, double speed)
    : m_model(model), m_time(time), m_speed(speed), m_jointed(model.bodies.size(), 0) {
  m_group.resize(model.bodies.size());
  std::iota(m_group.begin(), m_group.end(), 0);
  const auto root = [&](int b) {
    while (m_group[b] != b) b = m_group[b] = m_group[m_group[b]];
    return b;
  };
  for (const JointModel& joint : model.joints) {
    const int a = joint.a.body, b = joint.b.body;
    for (int e : {a, b})
      if (e >= 0) m_jointed[e] = 1;
    if (a < 0 || b < 0 || !model.bodies[a].carries_dofs() || !model.bodies[b].carries_dofs()) continue;
    const int ra = root(a), rb = root(b);
    m_group[std::max(ra, rb)] = std::min(ra, rb);
  }
  for (int b = 0; b < int(m_group.size()); ++b) m_group[b] = root(b);
  restore(State{});
}

void Sleeping::restore(const State& s) {
  const auto n = Eigen::Index(m_model.bodies.size());
  if (s.rest_time.size() == 0 && s.asleep.size() == 0) {
    m_state = {Eigen::VectorXd::Zero(n), Eigen::VectorXd::Constant(n, -1)};
    return;
  }
  if (s.rest_time.size() != n || s.asleep.size() != n)
    throw std::invalid_argument("Sleeping::restore: the state has " + std::to_string(s.rest_time.size()) +
                                " bodies' rest times and " + std::to_string(s.asleep.size()) +
                                " sleeping flags, this model " + std::to_string(n) + " bodies");
  m_state = s;
}

int Sleeping::sleeping_count() const { return int((m_state.asleep.array() >= 0).count()); }

bool Sleeping::all_asleep() const {
  for (int b = 0; b < int(m_model.bodies.size()); ++b) {
    const BodyModel& body = m_model.bodies[b];
    if (body.carries_dofs() && !(may_sleep(body) && asleep(b))) return false;
  }
  return true;
}

std::vector<char> Sleeping::still_bodies() const {
  std::vector<char> still(m_model.bodies.size(), 0);
  for (int b = 0; b < int(still.size()); ++b) still[b] = asleep(b) || !m_model.bodies[b].carries_dofs();
  return still;
}

std::vector<int> Sleeping::held_blocks() const {
  std::vector<int> blocks;
  for (int b = 0; b < int(m_model.bodies.size()); ++b)
    if (asleep(b)) blocks.push_back(m_model.bodies[b].block);
  return blocks;
}

std::vector<int> Sleeping::wake_near_moves(const Eigen::MatrixX3d& x_n, const Eigen::MatrixX3d& x_start,
                                           double dhat, double h) {
  return wake_reached(x_n, x_start, dhat, h, true);
}

std::vector<int> Sleeping::wake_met_by_moves(const Eigen::MatrixX3d& x_n, const Eigen::MatrixX3d& x_new,
                                             double dhat, double h) {
  return wake_reached(x_n, x_new, dhat, h, false);
}

std::vector<int> Sleeping::wake_reached(const Eigen::MatrixX3d& x_n, const Eigen::MatrixX3d& x_to,
                                        double dhat, double h, bool grow_by_move) {
  std::vector<int> sleeping;
  std::vector<AxisBox> swept;  // of the moving bodies
  for (int b = 0; b < int(m_model.bodies.size()); ++b) {
    const BodyModel& body = m_model.bodies[b];
    if (asleep(b)) {
      sleeping.push_back(b);
      continue;
    }
    if (!body.carries_dofs()) continue;
    double move = 0;
    for (int v = body.vertex_begin; v < body.vertex_end; ++v)
      move = std::max(move, (x_to.row(v) - x_n.row(v)).norm());
    if (move <= m_speed * h) continue;  // at rest as far as sleeping goes
    const double grow = grow_by_move ? dhat + move : dhat;
    const AxisBox from = body_box(body, x_n, grow), to = body_box(body, x_to, grow);
    swept.emplace_back(from.lo.min(to.lo), from.hi.max(to.hi));
  }
  std::vector<int> woken;
  if (swept.empty()) return woken;
  std::vector<char> group_woken(m_model.bodies.size(), 0);
  for (int b : sleeping) {
    const AxisBox box = body_box(m_model.bodies[b], x_n, dhat);
    if (std::any_of(swept.begin(), swept.end(), [&](const AxisBox& s) { return s.overlaps(box); }))
      group_woken[m_group[b]] = 1;
  }
  for (int b : sleeping) {
    if (!group_woken[m_group[b]]) continue;
    m_state.asleep[b] = -1;
    m_state.rest_time[b] = 0;  // it rests t_s again before it sleeps again
    woken.push_back(b);
  }
  return woken;
}

std::vector<int> Sleeping::end_step(const std::vector<ContactConstraint>& contacts,
                                    const Eigen::MatrixX3d& surface_velocity, double h) {
  const int nb = int(m_model.bodies.size());
  const std::vector<int>& vertex_body = m_model.mesh.vertex_body;
  std::vector<char> touching(std::size_t(nb), 0);
  for (const ContactConstraint& k : contacts)
    for (int v : k.vertices)
      if (v >= 0) touching[vertex_body[v]] = 1;
  for (int b = 0; b < nb; ++b) touching[b] |= m_jointed[b];
  for (int b = 0; b < nb; ++b) {
    const BodyModel& body = m_model.bodies[b];
    if (asleep(b) || !body.carries_dofs()) continue;
    double speed = 0;
    for (int v = body.vertex_begin; v < body.vertex_end; ++v)
      speed = std::max(speed, surface_velocity.row(v).norm());
    const bool resting = may_sleep(body) && touching[b] && speed <= m_speed;
    m_state.rest_time[b] = resting ? m_state.rest_time[b] + h : 0.0;
  }
  // Rested t_s, or asleep: what a body's dynamic neighbours must all be for it to sleep.
  const auto settled = [&](int b) {
    const BodyModel& body = m_model.bodies[b];
    return body.motion != Motion::Dynamic || asleep(b) || (may_sleep(body) && m_state.rest_time[b] >= m_time);
  };
  std::vector<char> sleeps(std::size_t(nb), 0);
  for (int b = 0; b < nb; ++b)
    sleeps[b] = may_sleep(m_model.bodies[b]) && !asleep(b) && m_state.rest_time[b] >= m_time;
  for (const ContactConstraint& k : contacts)
    for (int v : k.vertices) {
      if (v < 0 || !sleeps[vertex_body[v]]) continue;
      for (int w : k.vertices)
        if (w >= 0 && !settled(vertex_body[w])) sleeps[vertex_body[v]] = 0;
    }
  // A joint group sleeps whole or not at all (so a body sleeps only beside joined bodies that
  // have rested t_s too).
  std::vector<char> group_awake(std::size_t(nb), 0);
  for (int b = 0; b < nb; ++b)
    if (!sleeps[b] && !asleep(b)) group_awake[m_group[b]] = 1;
  std::vector<int> fell_asleep;
  for (int b = 0; b < nb; ++b)
    if (sleeps[b] && !group_awake[m_group[b]]) {
      m_state.asleep[b] = 1;
      fell_asleep.push_back(b);
    }
  return fell_asleep;
}

}  // namespace stiffsoft
