#include <stiffsoft/coupling/terms/damping_term.hpp>

#include <algorithm>
#include <cmath>

#include <stiffsoft/coupling/contact/barrier_potential.hpp>
#include <stiffsoft/coupling/joints/joint_measures.hpp>

namespace stiffsoft {

void DampingTerm::start_step(const Eigen::VectorXd& q_n, double beta_h) {
  m_q_n = q_n;
  m_beta_h = beta_h;
  m_contacts.clear();
  m_joints.clear();
}

double contact_pair_damping(const std::array<int, 2>& bodies, double k_d, const std::vector<ContactPairDamping>& pairs) {
  for (const ContactPairDamping& p : pairs)
    if ((p.body_a == bodies[0] && p.body_b == bodies[1]) || (p.body_a == bodies[1] && p.body_b == bodies[0]))
      return p.damping;
  return k_d;
}

void DampingTerm::lag_contact(const Configuration& c_n, const BarrierTerm& barrier, double k_d,
                              const std::vector<ContactPairDamping>& pairs, double beta_h2) {
  const bool any = k_d > 0 || std::any_of(pairs.begin(), pairs.end(), [](const ContactPairDamping& p) { return p.damping > 0; });
  if (!any) return;
  for (const ContactConstraint& k : barrier.constraints()) {
    // The stencil's bodies: its first vertex's and any other (one body for self-contact).
    std::array<int, 2> bodies{-1, -1};
    for (const int v : k.vertices) {
      if (v < 0) continue;
      const int b = m_model.mesh.vertex_body[v];
      if (bodies[0] < 0) bodies = {b, b};
      else if (b != bodies[0]) bodies[1] = b;
    }
    const double k_pair = pairs.empty() ? k_d : contact_pair_damping(bodies, k_d, pairs);
    if (k_pair <= 0) continue;
    // K = k_d ∇²B with B = (barrier value)/(β h²); times β h for the incremental potential.
    const double weight = m_beta_h * k_pair / beta_h2;
    const contact::Vector12d x_n = gather(c_n.x, k.vertices);
    const contact::Matrix12d H =
        barrier.kappa() * k.weight * contact::barrier_potential_hessian(k.stencil, x_n, barrier.dhat(), true);
    m_contacts.push_back({StencilJacobian(m_model, k.vertices), k.vertices, weight * H, x_n});
  }
}

void DampingTerm::lag_joints() {
  for (const JointModel& joint : m_model.joints) {
    if (joint.damping <= 0) continue;
    const double root = std::sqrt(m_beta_h * joint.damping);
    if (joint.kind == JointKind::Ball || joint.kind == JointKind::ConeTwist) {
      // The relative angular velocity ω_a − ω_b from the rates of both frames' columns.
      std::vector<JointVector> columns;
      for (const JointEnd* end : {&joint.a, &joint.b})
        for (int k = 0; k < 3; ++k) columns.push_back(end_direction(m_model, *end, Eigen::Vector3d::Unit(k)));
      JointVectors stack(std::move(columns));
      const Eigen::VectorXd y_n = stack.gather(m_q_n);
      m_joints.push_back({std::move(stack), root * relative_angular_velocity_jacobian(y_n), y_n});
      continue;
    }
    JointMeasure measure = JointMeasure::Distance;
    std::vector<JointVector> vectors;
    const JointVector xa = end_point(m_model, joint.a, joint.a.anchor), xb = end_point(m_model, joint.b, joint.b.anchor);
    switch (joint.kind) {
      case JointKind::Hinge:
        measure = JointMeasure::HingeAngle;
        vectors = {end_direction(m_model, joint.a, joint.a.reference), end_direction(m_model, joint.b, joint.b.reference),
                   end_direction(m_model, joint.a, joint.a.axis)};
        break;
      case JointKind::Prismatic:
        measure = JointMeasure::Slide;
        vectors = {xa, xb, end_direction(m_model, joint.b, joint.b.axis)};
        break;
      case JointKind::Distance:
      case JointKind::BoundedDistance: vectors = {xa, xb}; break;
      case JointKind::Ball:
      case JointKind::ConeTwist: break;  // above
    }
    JointVectors stack(std::move(vectors));
    const Eigen::VectorXd y_n = stack.gather(m_q_n);
    const MeasureValue m = measure_derivatives(measure, y_n);
    m_joints.push_back({std::move(stack), root * m.grad.transpose(), y_n});
  }
}

double DampingTerm::value(const Configuration& c) const {
  double e = 0;
  for (const ContactElement& k : m_contacts) {
    const contact::Vector12d dx = gather(c.x, k.vertices) - k.x_n;
    e += 0.5 * dx.dot(k.K * dx);
  }
  for (const JointElement& j : m_joints) e += 0.5 * (j.W * (j.vectors.gather(c.q) - j.y_n)).squaredNorm();
  return e;
}

void DampingTerm::add_gradient(const Configuration& c, Eigen::VectorXd& g) const {
  for (const ContactElement& k : m_contacts) {
    const contact::Vector12d dx = gather(c.x, k.vertices) - k.x_n;
    k.J.scatter_gradient(k.K * dx, g);
  }
  for (const JointElement& j : m_joints)
    j.vectors.scatter_gradient(j.W.transpose() * (j.W * (j.vectors.gather(c.q) - j.y_n)), g);
}

void DampingTerm::add_hessian(const Configuration&, BlockHessian& H) const {
  for (const ContactElement& k : m_contacts) k.J.scatter_hessian(k.K, H);
  for (const JointElement& j : m_joints) j.vectors.scatter_hessian(j.W.transpose() * j.W, H);
}

void DampingTerm::join_coupled_blocks(const Configuration&, const Eigen::MatrixX3d&, BlockIslands& islands) const {
  if (!m_joints.empty()) islands.join_all();
  for (const ContactElement& e : m_contacts) islands.join_blocks(e.J.block);
}

}  // namespace stiffsoft
