#include <stiffsoft/coupling/terms/joint_term.hpp>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

#include <stiffsoft/coupling/contact/barrier.hpp>

namespace stiffsoft {

namespace {
// IPC's barrier b(x) = −(x − 1)² ln x on the normalised gap x = g/ĝ (g in m or rad, ĝ the
// activation), so that κ b is an energy with κ in J whatever the unit of the gap:
// contact::barrier(s, d̂) is −(s − d̂²)² ln(s/d̂²), called with s = x and d̂ = 1.
double b(double g, double activation) { return contact::barrier(g / activation, 1.0); }
double db(double g, double activation) { return contact::barrier_first_derivative(g / activation, 1.0) / activation; }
double ddb(double g, double activation) {
  return contact::barrier_second_derivative(g / activation, 1.0) / (activation * activation);
}

Eigen::MatrixXd project_psd(const Eigen::MatrixXd& H) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(H);
  const Eigen::VectorXd lambda = es.eigenvalues().cwiseMax(0.0);
  return es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
}
}  // namespace

double JointPotential::gap(double s) const {
  if (wrap == JointWrap::LowerBarrier) return s - target;
  if (wrap == JointWrap::UpperBarrier) return target - s;
  return std::numeric_limits<double>::infinity();
}

double JointPotential::energy(double s) const {
  switch (wrap) {
    case JointWrap::Penalty: return 0.5 * k * (s - target) * (s - target);
    case JointWrap::HalfLinear: return 0.5 * k * s;
    case JointWrap::LowerBarrier:
    case JointWrap::UpperBarrier: return k * b(gap(s), activation);
  }
  return 0;
}

double JointPotential::first_derivative(double s) const {
  switch (wrap) {
    case JointWrap::Penalty: return k * (s - target);
    case JointWrap::HalfLinear: return 0.5 * k;
    case JointWrap::LowerBarrier: return k * db(gap(s), activation);
    case JointWrap::UpperBarrier: return -k * db(gap(s), activation);
  }
  return 0;
}

double JointPotential::second_derivative(double s) const {
  switch (wrap) {
    case JointWrap::Penalty: return k;
    case JointWrap::HalfLinear: return 0;
    case JointWrap::LowerBarrier:
    case JointWrap::UpperBarrier: return k * ddb(gap(s), activation);
  }
  return 0;
}

std::vector<std::pair<JointPotential, JointVectors>> joint_potentials(const Model& model) {
  std::vector<std::pair<JointPotential, JointVectors>> out;
  for (int j = 0; j < int(model.joints.size()); ++j) {
    const JointModel& joint = model.joints[j];
    const auto add_limits = [&](JointMeasure measure, const JointVectors& vectors) {
      if (joint.lower)
        out.emplace_back(JointPotential{j, measure, JointWrap::LowerBarrier, joint.limit_stiffness, *joint.lower,
                                        joint.limit_activation},
                         vectors);
      if (joint.upper)
        out.emplace_back(JointPotential{j, measure, JointWrap::UpperBarrier, joint.limit_stiffness, *joint.upper,
                                        joint.limit_activation},
                         vectors);
    };
    const JointVector xa = end_point(model, joint.a, joint.a.anchor), xb = end_point(model, joint.b, joint.b.anchor);
    switch (joint.kind) {
      case JointKind::Ball: break;
      case JointKind::Hinge:
        add_limits(JointMeasure::HingeAngle,
                   JointVectors({end_direction(model, joint.a, joint.a.reference),
                                 end_direction(model, joint.b, joint.b.reference),
                                 end_direction(model, joint.a, joint.a.axis)}));
        break;
      case JointKind::Prismatic: {
        const JointVectors vectors({xa, xb, end_direction(model, joint.b, joint.b.axis)});
        out.emplace_back(JointPotential{j, JointMeasure::OffAxis, JointWrap::HalfLinear, joint.stiffness, 0, 0}, vectors);
        add_limits(JointMeasure::Slide, vectors);
        break;
      }
      case JointKind::Distance:
        out.emplace_back(JointPotential{j, JointMeasure::Distance, JointWrap::Penalty, joint.stiffness,
                                        joint.rest_length, 0},
                         JointVectors({xa, xb}));
        break;
      case JointKind::BoundedDistance: add_limits(JointMeasure::Distance, JointVectors({xa, xb})); break;
      case JointKind::ConeTwist: {
        const JointVector ea = end_direction(model, joint.a, joint.a.axis), eb = end_direction(model, joint.b, joint.b.axis);
        if (joint.swing)
          out.emplace_back(JointPotential{j, JointMeasure::BendAngle, JointWrap::UpperBarrier, joint.limit_stiffness,
                                          *joint.swing, joint.limit_activation},
                           JointVectors({ea, eb}));
        add_limits(JointMeasure::TwistAngle,
                   JointVectors({ea, eb, end_direction(model, joint.a, joint.a.reference),
                                 end_direction(model, joint.b, joint.b.reference)}));
        break;
      }
    }
  }
  return out;
}

JointTerm::JointTerm(const Model& model, double scale) : m_potentials(joint_potentials(model)), m_scale(scale) {}

double JointTerm::value(const Configuration& c) const {
  double e = 0;
  for (const auto& [p, v] : m_potentials) e += p.energy(measure(p.measure, v.gather(c.q)));
  return m_scale * e;
}

bool JointPotential::inactive(double s) const {
  return (wrap == JointWrap::LowerBarrier || wrap == JointWrap::UpperBarrier) && gap(s) >= activation;
}

void JointTerm::add_gradient(const Configuration& c, Eigen::VectorXd& g) const {
  for (const auto& [p, v] : m_potentials) {
    const Eigen::VectorXd y = v.gather(c.q);
    if (p.inactive(measure(p.measure, y))) continue;
    const MeasureValue m = measure_derivatives(p.measure, y);
    v.scatter_gradient(m_scale * p.first_derivative(m.s) * m.grad, g);
  }
}

void JointTerm::add_hessian(const Configuration& c, BlockHessian& H) const {
  for (const auto& [p, v] : m_potentials) {
    const Eigen::VectorXd y = v.gather(c.q);
    if (p.inactive(measure(p.measure, y))) continue;
    const MeasureValue m = measure_derivatives(p.measure, y);
    const Eigen::MatrixXd H_y =
        p.second_derivative(m.s) * m.grad * m.grad.transpose() + p.first_derivative(m.s) * m.hess;
    v.scatter_hessian(m_scale * project_psd(H_y), H);
  }
}

double JointTerm::max_step(const Configuration& c, const Eigen::VectorXd& dq, const Eigen::MatrixX3d&) const {
  double alpha = 1;
  for (const auto& [p, v] : m_potentials) {
    if (p.wrap != JointWrap::LowerBarrier && p.wrap != JointWrap::UpperBarrier) continue;
    const Eigen::VectorXd y0 = v.gather(c.q);
    const Eigen::VectorXd dy = v.gather(c.q + dq) - y0;  // y is affine in q
    const double s0 = measure(p.measure, y0), g0 = p.gap(s0);
    for (int halving = 0; halving < 60; ++halving) {
      bool ok = true;
      double previous = s0;
      for (int k = 1; k <= 8 && ok; ++k) {
        const double s = measure(p.measure, y0 + (alpha * k / 8.0) * dy);
        ok = p.gap(s) >= 0.1 * g0 && std::abs(s - previous) < 0.5;
        previous = s;
      }
      if (ok) break;
      alpha *= 0.5;
    }
  }
  return alpha;
}

std::vector<double> JointTerm::joint_energies(const Eigen::VectorXd& q, int joints) const {
  std::vector<double> e(joints, 0.0);
  for (const auto& [p, v] : m_potentials) e[p.joint] += p.energy(measure(p.measure, v.gather(q)));
  return e;
}

}  // namespace stiffsoft
