#include <stiffsoft/coupling/terms/inertia_term.hpp>

namespace stiffsoft {

InertiaTerm::InertiaTerm(const Model& model, double kinematic_weight) : m_q_tilde(model.initial_q()) {
  const auto weight = [&](Motion m) { return m == Motion::Kinematic ? kinematic_weight : 1.0; };
  for (const BodyModel& body : model.bodies)
    if (body.dof >= 0) m_affine.push_back({body.block, body.dof, weight(body.motion) * body.M});
  for (int i = 0; i < model.nodes.size(); ++i)
    if (model.nodes.dof[i] >= 0)
      m_nodes.push_back({model.nodes.block[i], model.nodes.dof[i], weight(model.nodes.motion[i]) * model.nodes.mass[i]});
}

double InertiaTerm::value(const Configuration& c) const {
  double e = 0;
  for (const AffineBlock& b : m_affine) {
    const abd::Vector12d d = c.q.segment<12>(b.dof) - m_q_tilde.segment<12>(b.dof);
    e += 0.5 * d.dot(b.M * d);
  }
  for (const NodeBlock& n : m_nodes)
    e += 0.5 * n.m * (c.q.segment<3>(n.dof) - m_q_tilde.segment<3>(n.dof)).squaredNorm();
  return e;
}

void InertiaTerm::add_gradient(const Configuration& c, Eigen::VectorXd& g) const {
  for (const AffineBlock& b : m_affine)
    g.segment<12>(b.dof) += b.M * (c.q.segment<12>(b.dof) - m_q_tilde.segment<12>(b.dof));
  for (const NodeBlock& n : m_nodes)
    g.segment<3>(n.dof) += n.m * (c.q.segment<3>(n.dof) - m_q_tilde.segment<3>(n.dof));
}

void InertiaTerm::add_hessian(const Configuration&, BlockHessian& H) const {
  for (const AffineBlock& b : m_affine) H.add(b.block, b.block, b.M);
  for (const NodeBlock& n : m_nodes) {
    const Eigen::Matrix3d M = n.m * Eigen::Matrix3d::Identity();
    H.add(n.block, n.block, M);
  }
}

}  // namespace stiffsoft
