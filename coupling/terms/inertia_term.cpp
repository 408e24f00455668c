#include "coupling/terms/inertia_term.hpp"

namespace stiffsoft {

InertiaTerm::InertiaTerm(const Model& model, double kinematic_weight)
    : m_M(model.num_dofs / 12), m_q_tilde(model.initial_q()) {
  for (const BodyModel& body : model.bodies)
    if (body.dof >= 0)
      m_M[body.dof / 12] = (body.motion == Motion::Kinematic ? kinematic_weight : 1.0) * body.M;
}

double InertiaTerm::value(const Configuration& c) const {
  double e = 0;
  for (size_t b = 0; b < m_M.size(); ++b) {
    const abd::Vector12d d = c.q.segment<12>(12 * b) - m_q_tilde.segment<12>(12 * b);
    e += 0.5 * d.dot(m_M[b] * d);
  }
  return e;
}

void InertiaTerm::add_gradient(const Configuration& c, Eigen::VectorXd& g) const {
  for (size_t b = 0; b < m_M.size(); ++b)
    g.segment<12>(12 * b) += m_M[b] * (c.q.segment<12>(12 * b) - m_q_tilde.segment<12>(12 * b));
}

void InertiaTerm::add_hessian(const Configuration&, BlockHessian& H) const {
  for (size_t b = 0; b < m_M.size(); ++b) H.add(int(b), int(b), m_M[b]);
}

}  // namespace stiffsoft
