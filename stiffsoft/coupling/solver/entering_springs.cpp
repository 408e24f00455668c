#include <stiffsoft/coupling/solver/entering_springs.hpp>

#include <algorithm>
#include <utility>

namespace stiffsoft {

EnteringSprings::EnteringSprings(const Model& model, std::vector<EnteringPair> pairs)
    : m_model(model), m_pairs(std::move(pairs)) {
  for (const EnteringPair& e : m_pairs) {
    const StencilJacobian& J = m_jacobians.emplace_back(m_model, e.vertices);
    double mass = 0;  // of what moves: fixed bodies and nodes carry no DOFs
    for (int a = 0; a < 4; ++a) {
      if (J.slot_of[std::size_t(a)] < 0) continue;
      const int v = e.vertices[std::size_t(a)], node = m_model.mesh.vertex_node[std::size_t(v)];
      mass = std::max(mass, node >= 0 ? m_model.nodes.mass[node]
                                      : m_model.bodies[std::size_t(m_model.mesh.vertex_body[std::size_t(v)])].mass);
    }
    m_stiffness.push_back(kSpringScale * mass);
  }
}

void EnteringSprings::add_hessian(std::size_t i, double sign, BlockHessian& H) const {
  StencilHessian blocks;
  const Eigen::Matrix<double, 1, 12> B = m_pairs[i].normal.transpose();
  const Eigen::Matrix<double, 1, 1> C = Eigen::Matrix<double, 1, 1>::Constant(sign * m_stiffness[i]);
  m_jacobians[i].low_rank_block_hessians<1>(B, C, blocks);
  blocks.add_to(H);
}

bool EnteringSprings::solve(BlockHessian& H, const Eigen::VectorXd& g, const Solve& solve_h, Eigen::VectorXd& p) {
  const std::size_t n = m_pairs.size();
  std::vector<char> acting(n, 1), in_h(n, 0);
  Eigen::VectorXd p_springs = p;
  bool solved = true;
  for (int round = 0; round < kRounds && solved; ++round) {
    Eigen::VectorXd g_springs = g;  // the model's gradient at p = 0: Σ kᵢ sᵢ Jᵢᵀ nᵢ over the acting springs
    for (std::size_t i = 0; i < n; ++i) {
      if (acting[i] != in_h[i]) add_hessian(i, acting[i] ? 1.0 : -1.0, H);
      in_h[i] = acting[i];
      if (acting[i]) m_jacobians[i].scatter_gradient(m_stiffness[i] * m_pairs[i].slack * m_pairs[i].normal, g_springs);
    }
    solved = solve_h(g_springs, p_springs);
    if (!solved) break;
    bool changed = false;
    for (std::size_t i = 0; i < n; ++i) {
      const bool closes = m_pairs[i].normal.dot(m_jacobians[i].step(p_springs)) + m_pairs[i].slack < 0;
      const char next = round < kFreeRounds ? char(closes) : char(acting[i] || closes);
      changed = changed || next != acting[i];
      acting[i] = next;
    }
    if (!changed) break;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (in_h[i]) add_hessian(i, -1.0, H);
  if (!solved || !(g.dot(p_springs) < 0)) return false;
  p.swap(p_springs);
  return true;
}

}  // namespace stiffsoft
