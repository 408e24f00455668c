#include <stiffsoft/coupling/contact/swept_candidates.hpp>

namespace stiffsoft {

SweptCandidates::SweptCandidates(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                                 double proximity, double slack, BroadPhase& finder)
    : m_lo(x0.array().min(x1.array())),
      m_hi(x0.array().max(x1.array())),
      m_slack(slack),
      m_all(finder.find(model, x0, x1, proximity + slack, &m_ccd)) {}

bool SweptCandidates::covers(const Eigen::MatrixX3d& x) const {
  if (x.rows() != m_lo.rows()) return false;
  return ((x.array() >= m_lo - m_slack).all() && (x.array() <= m_hi + m_slack).all());
}

}  // namespace stiffsoft
