#include <stiffsoft/coupling/ccd/edge_edge_ccd.hpp>

#include <stiffsoft/coupling/ccd/additive_ccd.hpp>
#include <stiffsoft/coupling/ccd/distance.hpp>
#include <stiffsoft/coupling/contact/distance_classification.hpp>

namespace stiffsoft::ccd {

double edge_edge_toi(const Eigen::Vector3d& ea0_t0, const Eigen::Vector3d& ea1_t0,
                     const Eigen::Vector3d& eb0_t0, const Eigen::Vector3d& eb1_t0,
                     const Eigen::Vector3d& ea0_t1, const Eigen::Vector3d& ea1_t1,
                     const Eigen::Vector3d& eb0_t1, const Eigen::Vector3d& eb1_t1,
                     const CcdSettings& settings) {
  validate(settings);
  return detail::additive_ccd<2>(
      {ea0_t0, ea1_t0, eb0_t0, eb1_t0}, {ea0_t1, ea1_t1, eb0_t1, eb1_t1}, settings,
      [](const detail::Stencil& x) {
        return detail::segment_segment_distance_squared<double>(x[0], x[1], x[2], x[3]);
      },
      [](const detail::Stencil& x) { return contact::line_line_squared_distance_lower_bound(x[0], x[1], x[2], x[3]); },
      [](const detail::Stencil& x) { return contact::segment_segment_squared_distance_lower_bound(x[0], x[1], x[2], x[3]); });
}

bool edge_edge_may_collide(const Eigen::Vector3d& ea0_t0, const Eigen::Vector3d& ea1_t0,
                           const Eigen::Vector3d& eb0_t0, const Eigen::Vector3d& eb1_t0,
                           const Eigen::Vector3d& ea0_t1, const Eigen::Vector3d& ea1_t1,
                           const Eigen::Vector3d& eb0_t1, const Eigen::Vector3d& eb1_t1,
                           const CcdSettings& settings) {
  return edge_edge_toi(ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1,
                       settings) < settings.t_max;
}

}  // namespace stiffsoft::ccd
