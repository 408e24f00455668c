#include <stiffsoft/coupling/terms/inertia_term.hpp>

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

double InertiaTerm::value(const Configuration& c) const {
  double e = 0;
  for (const AffineBlock& b : m_affine) {
    const abd::Vector12d d = c.q.segment<12>(b.dof) - m_q_tilde.segment<12>(b.dof);
    e += 0.5 * weight(b.kinematic) * d.dot(b.M * d);
  }
  for (const NodeBlock& n : m_nodes)
    e += 0.5 * weight(n.kinematic) * n.m * (c.q.segment<3>(n.dof) - m_q_tilde.segment<3>(n.dof)).squaredNorm();
  return e;
}

void InertiaTerm::add_gradient(const Configuration& c, Eigen::VectorXd& g) const {
  for (const AffineBlock& b : m_affine)
    g.segment<12>(b.dof) += weight(b.kinematic) * b.M * (c.q.segment<12>(b.dof) - m_q_tilde.segment<12>(b.dof));
  for (const NodeBlock& n : m_nodes)
    g.segment<3>(n.dof) += weight(n.kinematic) * n.m * (c.q.segment<3>(n.dof) - m_q_tilde.segment<3>(n.dof));
}

void InertiaTerm::add_hessian(const Configuration&, BlockHessian& H) const {
  for (const AffineBlock& b : m_affine) H.add(b.block, b.block, weight(b.kinematic) * b.M);
  for (const NodeBlock& n : m_nodes) {
    const Eigen::Matrix3d M = weight(n.kinematic) * n.m * Eigen::Matrix3d::Identity();
    H.add(n.block, n.block, M);
  }
}

}  // namespace stiffsoft
