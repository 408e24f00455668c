#include <stiffsoft/coupling/contact/swept_candidates.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace stiffsoft {

SweptCandidates::SweptCandidates(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                                 double proximity, double slack, BroadPhase& finder)
    : m_lo(x0.array().min(x1.array())),
      m_hi(x0.array().max(x1.array())),
      m_slack(slack),
      m_all(finder.find(model, x0, x1, proximity + slack, &m_ccd)) {}

bool SweptCandidates::covers(const Eigen::MatrixX3d& x) const {
  if (x.rows() != m_lo.rows()) return false;
  // By ranges of points in parallel: every trial of the line search asks.
  return tbb::parallel_reduce(
      tbb::blocked_range<Eigen::Index>(0, x.rows(), 4096), true,
      [&](const tbb::blocked_range<Eigen::Index>& r, bool inside) {
        const Eigen::Index begin = r.begin(), n = r.end() - r.begin();
        return inside && (x.middleRows(begin, n).array() >= m_lo.middleRows(begin, n) - m_slack).all() &&
               (x.middleRows(begin, n).array() <= m_hi.middleRows(begin, n) + m_slack).all();
      },
      [](bool a, bool b) { return a && b; });
}

}  // namespace stiffsoft
