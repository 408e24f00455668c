#include <stiffsoft/coupling/contact/clear_motion.hpp>

#include <stiffsoft/coupling/ccd/additive_ccd.hpp>

#include <algorithm>
#include <cmath>

namespace stiffsoft {

ClearMotion::ClearMotion(const std::vector<ContactConstraint>& constraints, const Eigen::MatrixX3d& x0,
                         const Eigen::MatrixX3d& x1, double dhat, const ccd::CcdSettings& settings)
    : m_clearance(std::size_t(x0.rows()), dhat), m_reach(std::size_t(x0.rows())), m_keep(1 - settings.tolerance) {
  for (const ContactConstraint& k : constraints)
    for (int v : k.vertices)
      if (v >= 0) m_clearance[std::size_t(v)] = std::min(m_clearance[std::size_t(v)], k.distance);
  double scale = 0;  // the largest coordinate of any query, for ACCD's rounding allowance
  for (Eigen::Index v = 0; v < x0.rows(); ++v) {
    m_reach[std::size_t(v)] = (x1.row(v) - x0.row(v)).norm();
    scale = std::max({scale, x0.row(v).cwiseAbs().maxCoeff(), x1.row(v).cwiseAbs().maxCoeff()});
  }
  m_allowance = settings.min_distance + 2 * ccd::detail::kRoundingAllowance * scale;
}

}  // namespace stiffsoft
