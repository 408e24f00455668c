#include <stiffsoft/coupling/ccd/point_triangle_ccd.hpp>

#include <stiffsoft/coupling/ccd/additive_ccd.hpp>
#include <stiffsoft/coupling/ccd/distance.hpp>
#include <stiffsoft/coupling/contact/distance_classification.hpp>

namespace stiffsoft::ccd {

double point_triangle_toi(const Eigen::Vector3d& p_t0, const Eigen::Vector3d& t0_t0,
                          const Eigen::Vector3d& t1_t0, const Eigen::Vector3d& t2_t0,
                          const Eigen::Vector3d& p_t1, const Eigen::Vector3d& t0_t1,
                          const Eigen::Vector3d& t1_t1, const Eigen::Vector3d& t2_t1,
                          const CcdSettings& settings) {
  validate(settings);
  return detail::additive_ccd<1>(
      {p_t0, t0_t0, t1_t0, t2_t0}, {p_t1, t0_t1, t1_t1, t2_t1}, settings,
      [](const detail::Stencil& x) {
        return detail::point_triangle_distance_squared<double>(x[0], x[1], x[2], x[3]);
      },
      [](const detail::Stencil& x) { return contact::point_triangle_squared_distance_lower_bound(x[0], x[1], x[2], x[3]); });
}

bool point_triangle_may_collide(const Eigen::Vector3d& p_t0, const Eigen::Vector3d& t0_t0,
                                const Eigen::Vector3d& t1_t0, const Eigen::Vector3d& t2_t0,
                                const Eigen::Vector3d& p_t1, const Eigen::Vector3d& t0_t1,
                                const Eigen::Vector3d& t1_t1, const Eigen::Vector3d& t2_t1,
                                const CcdSettings& settings) {
  return point_triangle_toi(p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1, t2_t1, settings) <
         settings.t_max;
}

}  // namespace stiffsoft::ccd
