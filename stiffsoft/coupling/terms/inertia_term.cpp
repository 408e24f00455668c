#include <stiffsoft/coupling/terms/inertia_term.hpp>
#include <stiffsoft/coupling/terms/ordered_sum.hpp>

namespace stiffsoft {

InertiaTerm::InertiaTerm(const Model& model, double kinematic_weight)
    : m_q_tilde(model.initial_q()), m_kinematic_weight(kinematic_weight) {
  for (const BodyModel& body : model.bodies)
    if (body.dof >= 0) m_affine.push_back({body.block, body.dof, body.M, body.motion == Motion::Kinematic});
  for (int i = 0; i < model.nodes.size(); ++i)
    if (model.nodes.dof[i] >= 0)
      m_nodes.push_back({model.nodes.block[i], model.nodes.dof[i], model.nodes.mass[i],
                         model.nodes.motion[i] == Motion::Kinematic});
}

// Bodies and nodes in parallel: each writes only its own segment of g and its own diagonal
// block of H, and the energy is summed in their order (ordered_sum.hpp).
namespace {
constexpr std::size_t kBodyGrain = 32, kNodeGrain = 256;
}  // namespace

double InertiaTerm::value(const Configuration& c) const {
  const double e = ordered_sum(0.0, m_affine.size(), kBodyGrain, [&](std::size_t k) {
    const AffineBlock& b = m_affine[k];
    const abd::Vector12d d = c.q.segment<12>(b.dof) - m_q_tilde.segment<12>(b.dof);
    return 0.5 * weight(b.kinematic) * d.dot(b.M * d);
  });
  return ordered_sum(e, m_nodes.size(), kNodeGrain, [&](std::size_t k) {
    const NodeBlock& n = m_nodes[k];
    return 0.5 * weight(n.kinematic) * n.m * (c.q.segment<3>(n.dof) - m_q_tilde.segment<3>(n.dof)).squaredNorm();
  });
}

void InertiaTerm::add_gradient(const Configuration& c, Eigen::VectorXd& g) const {
  for_each_item(m_affine.size(), kBodyGrain, [&](std::size_t k) {
    const AffineBlock& b = m_affine[k];
    g.segment<12>(b.dof) += weight(b.kinematic) * b.M * (c.q.segment<12>(b.dof) - m_q_tilde.segment<12>(b.dof));
  });
  for_each_item(m_nodes.size(), kNodeGrain, [&](std::size_t k) {
    const NodeBlock& n = m_nodes[k];
    g.segment<3>(n.dof) += weight(n.kinematic) * n.m * (c.q.segment<3>(n.dof) - m_q_tilde.segment<3>(n.dof));
  });
}

void InertiaTerm::add_hessian(const Configuration&, BlockHessian& H) const {
  for_each_item(m_affine.size(), kBodyGrain, [&](std::size_t k) {
    const AffineBlock& b = m_affine[k];
    H.add(b.block, b.block, weight(b.kinematic) * b.M);
  });
  for_each_item(m_nodes.size(), kNodeGrain, [&](std::size_t k) {
    const NodeBlock& n = m_nodes[k];
    const Eigen::Matrix3d M = weight(n.kinematic) * n.m * Eigen::Matrix3d::Identity();
    H.add(n.block, n.block, M);
  });
}

}  // namespace stiffsoft
