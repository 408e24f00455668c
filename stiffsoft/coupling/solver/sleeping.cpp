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

/// Whether body b carries DOFs (a dynamic or kinematic affine body, a soft body).
bool carries_dofs(const BodyModel& body) {
  return body.dof >= 0 || body.representation == Representation::Soft;
}

/// Whether body b may sleep: a dynamic affine body.
bool may_sleep(const BodyModel& body) {
  return body.representation == Representation::Affine && body.motion == Motion::Dynamic && body.dof >= 0;
}

/// Union–find over bodies.
class BodySets {
 public:
  explicit BodySets(int n) : m_parent(std::size_t(n)) { std::iota(m_parent.begin(), m_parent.end(), 0); }
  int root(int b) {
    while (m_parent[b] != b) b = m_parent[b] = m_parent[m_parent[b]];
    return b;
  }
  void join(int a, int b) {
    a = root(a), b = root(b);
    if (a != b) m_parent[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> m_parent;
};

}  // namespace

Sleeping::Sleeping(const Model& model, double time, double speed)
    : m_model(model), m_time(time), m_speed(speed) {
  restore(State{});
}

void Sleeping::restore(const State& s) {
  const auto n = Eigen::Index(m_model.bodies.size());
  if (s.rest_time.size() == 0 && s.island.size() == 0) {
    m_state = {Eigen::VectorXd::Zero(n), Eigen::VectorXd::Constant(n, -1)};
    return;
  }
  if (s.rest_time.size() != n || s.island.size() != n)
    throw std::invalid_argument("Sleeping::restore: the state has " + std::to_string(s.rest_time.size()) +
                                " bodies' rest times and " + std::to_string(s.island.size()) +
                                " islands, this model " + std::to_string(n) + " bodies");
  m_state = s;
}

int Sleeping::sleeping_count() const { return int((m_state.island.array() >= 0).count()); }

bool Sleeping::all_asleep() const {
  for (int b = 0; b < int(m_model.bodies.size()); ++b) {
    const BodyModel& body = m_model.bodies[b];
    if (carries_dofs(body) && !(may_sleep(body) && asleep(b))) return false;
  }
  return true;
}

std::vector<char> Sleeping::still_bodies() const {
  std::vector<char> still(m_model.bodies.size(), 0);
  for (int b = 0; b < int(still.size()); ++b) still[b] = asleep(b) || !carries_dofs(m_model.bodies[b]);
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
  std::vector<int> sleeping;
  std::vector<AxisBox> swept;  // of the moving bodies
  for (int b = 0; b < int(m_model.bodies.size()); ++b) {
    const BodyModel& body = m_model.bodies[b];
    if (asleep(b)) {
      sleeping.push_back(b);
      continue;
    }
    if (!carries_dofs(body)) continue;
    double move = 0;
    for (int v = body.vertex_begin; v < body.vertex_end; ++v)
      move = std::max(move, (x_start.row(v) - x_n.row(v)).norm());
    if (move <= m_speed * h) continue;  // at rest as far as sleeping goes: it wakes others by touching them
    const AxisBox from = body_box(body, x_n, dhat + move), to = body_box(body, x_start, dhat + move);
    swept.emplace_back(from.lo.min(to.lo), from.hi.max(to.hi));
  }
  if (sleeping.empty() || swept.empty()) return {};
  std::vector<double> woken_islands;
  for (int b : sleeping) {
    const AxisBox box = body_box(m_model.bodies[b], x_n, dhat);
    if (std::any_of(swept.begin(), swept.end(), [&](const AxisBox& s) { return s.overlaps(box); }))
      woken_islands.push_back(m_state.island[b]);
  }
  std::vector<int> woken;
  for (int b : sleeping)
    if (std::find(woken_islands.begin(), woken_islands.end(), m_state.island[b]) != woken_islands.end()) {
      m_state.island[b] = -1;
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
  BodySets sets(nb);
  for (const ContactConstraint& k : contacts) {
    int first = -1;
    for (int v : k.vertices) {
      if (v < 0) continue;
      const int b = vertex_body[v];
      touching[b] = 1;
      if (m_model.bodies[b].motion != Motion::Dynamic) continue;  // fixed and kinematic bodies join no island
      if (first < 0)
        first = b;
      else
        sets.join(first, b);
    }
  }
  std::vector<int> first_of_island(std::size_t(nb), -1);  // a sleeping island's stays whole
  for (int b = 0; b < nb; ++b) {
    if (!asleep(b)) continue;
    int& first = first_of_island[std::size_t(m_state.island[b])];
    if (first < 0)
      first = b;
    else
      sets.join(first, b);
  }
  for (int b = 0; b < nb; ++b) {
    const BodyModel& body = m_model.bodies[b];
    if (asleep(b) || !carries_dofs(body)) continue;
    double speed = 0;
    for (int v = body.vertex_begin; v < body.vertex_end; ++v)
      speed = std::max(speed, surface_velocity.row(v).norm());
    const bool resting = may_sleep(body) && touching[b] && speed <= m_speed;
    m_state.rest_time[b] = resting ? m_state.rest_time[b] + h : 0.0;
  }
  // An island sleeps when all its bodies may and have rested t_s; it is labelled by its root
  // (its smallest body index).
  std::vector<char> sleeps(std::size_t(nb), 1);
  for (int b = 0; b < nb; ++b) {
    const BodyModel& body = m_model.bodies[b];
    if (body.motion != Motion::Dynamic) continue;
    if (!may_sleep(body) || m_state.rest_time[b] < m_time) sleeps[std::size_t(sets.root(b))] = 0;
  }
  std::vector<int> fell_asleep;
  for (int b = 0; b < nb; ++b) {
    if (!may_sleep(m_model.bodies[b])) continue;
    const int root = sets.root(b);
    const double label = sleeps[std::size_t(root)] ? double(root) : -1.0;
    if (label >= 0 && !asleep(b)) fell_asleep.push_back(b);
    m_state.island[b] = label;
  }
  return fell_asleep;
}

}  // namespace stiffsoft
