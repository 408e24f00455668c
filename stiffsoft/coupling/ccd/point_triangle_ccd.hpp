#pragma once
/// @file Conservative linear CCD of a point against a triangle (Additive CCD, Li, Kaufman, Jiang
/// 2021, §5). Every vertex moves on a straight line from its t = 0 to its t = 1 position, which is
/// exact for affine bodies and tets within one Newton step.

#include <Eigen/Core>

#include <stiffsoft/coupling/ccd/ccd_settings.hpp>

namespace stiffsoft::ccd {

/// Earliest time of impact of point p moving p_t0 → p_t1 against triangle (t0, t1, t2) moving
/// t*_t0 → t*_t1, all linear in t ∈ [0, settings.t_max] (positions in metres).
/// Returns settings.t_max when the distance stays above ξ = settings.min_distance on the whole
/// interval. Otherwise returns toi ∈ [0, t_max), strictly before the first contact (distance ≤ ξ),
/// at which the distance is still ≥ ξ + s·(d₀ − ξ) (s = settings.tolerance, d₀ the initial
/// distance); toi = 0 when d₀ ≤ ξ. Near misses closer than about that gap, and queries that hit
/// settings.max_iterations, are also reported with such a collision-free toi (false positives);
/// a contact is never missed.
double point_triangle_toi(const Eigen::Vector3d& p_t0, const Eigen::Vector3d& t0_t0,
                          const Eigen::Vector3d& t1_t0, const Eigen::Vector3d& t2_t0,
                          const Eigen::Vector3d& p_t1, const Eigen::Vector3d& t0_t1,
                          const Eigen::Vector3d& t1_t1, const Eigen::Vector3d& t2_t1,
                          const CcdSettings& settings);

/// True when the point–triangle motion may come into contact in [0, t_max], i.e. when
/// point_triangle_toi(...) < settings.t_max; false means it is certainly contact-free.
bool point_triangle_may_collide(const Eigen::Vector3d& p_t0, const Eigen::Vector3d& t0_t0,
                                const Eigen::Vector3d& t1_t0, const Eigen::Vector3d& t2_t0,
                                const Eigen::Vector3d& p_t1, const Eigen::Vector3d& t0_t1,
                                const Eigen::Vector3d& t1_t1, const Eigen::Vector3d& t2_t1,
                                const CcdSettings& settings);

}  // namespace stiffsoft::ccd
