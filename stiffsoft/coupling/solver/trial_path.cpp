#include <stiffsoft/coupling/solver/trial_path.hpp>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <stiffsoft/libabd/affine_body.hpp>
#include <stiffsoft/libabd/orthogonality_potential.hpp>

namespace stiffsoft {

TrialPath::TrialPath(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& p, bool geodesic, double decrease)
    : m_q(q), m_p(p) {
  if (!geodesic) return;
  for (const BodyModel& body : model.bodies) {
    if (body.dof < 0 || body.motion != Motion::Dynamic) continue;
    const abd::Vector12d q_b = q.segment<12>(body.dof), p_b = p.segment<12>(body.dof);
    const Eigen::Vector3d w = abd::angular_velocity(q_b, p_b);  // W's axial vector
    // The orthogonality energy the straight line adds by turning the body, unseen by the model:
    // κ ν ‖W Wᵀ‖²_F = 2 κ ν |w|⁴.
    const double stretch = 2 * body.kappa * body.volume * w.squaredNorm() * w.squaredNorm();
    if (w.squaredNorm() == 0 || stretch < decrease) continue;
    const Eigen::Matrix3d A = abd::affine_matrix(q_b);
    const Eigen::Matrix3d M = abd::affine_matrix(p_b) * A.inverse();
    m_turns.push_back({body.dof, body.block, body.kappa * body.volume, A, w, 0.5 * (M + M.transpose())});
  }
}

Eigen::Matrix3d TrialPath::turned(const Turn& t, double alpha) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(alpha * t.w.norm(), t.w.normalized()).toRotationMatrix();
  return R * (Eigen::Matrix3d::Identity() + alpha * t.S) * t.A;
}

void TrialPath::point(double alpha, Eigen::VectorXd& out) const {
  out = m_q + alpha * m_p;
  for (const Turn& t : m_turns) out.segment<12>(t.dof) = abd::make_q(out.segment<3>(t.dof), turned(t, alpha));
}

void TrialPath::point(const Model& model, const std::vector<double>& alpha, Eigen::VectorXd& out) const {
  out = m_q;
  for (std::size_t b = 0; b < model.blocks.size(); ++b)
    out.segment(model.blocks[b].offset, model.blocks[b].size) +=
        alpha[b] * m_p.segment(model.blocks[b].offset, model.blocks[b].size);
  for (const Turn& t : m_turns)
    out.segment<12>(t.dof) = abd::make_q(out.segment<3>(t.dof), turned(t, alpha[std::size_t(t.block)]));
}

double TrialPath::chord_stretch(const BlockIslands& islands, const std::vector<double>& bound, double alpha) const {
  // V⊥ of the chord's point against the path's (it depends on A only).
  const auto V = [](const Turn& t, const Eigen::Matrix3d& A) {
    return abd::orthogonality_potential(abd::make_q(Eigen::Vector3d::Zero(), A), t.kappa_volume, 1.0);
  };
  double excess = 0;
  for (const Turn& t : m_turns) {
    const double beta = bound[std::size_t(islands.island(t.block))];
    if (beta >= 1) continue;
    excess += V(t, t.A + beta * (turned(t, alpha) - t.A)) - V(t, turned(t, alpha * beta));
  }
  return excess;
}

}  // namespace stiffsoft
