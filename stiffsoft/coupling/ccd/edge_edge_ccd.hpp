#pragma once
/// @file Conservative linear CCD of two edges (segments), Additive CCD (Li, Kaufman, Jiang 2021,
/// §5). Every vertex moves on a straight line from its t = 0 to its t = 1 position.

#include <Eigen/Core>

#include <stiffsoft/coupling/ccd/ccd_settings.hpp>

namespace stiffsoft::ccd {

/// Earliest time of impact of edge (ea0, ea1) against edge (eb0, eb1), each vertex moving
/// linearly from its *_t0 to its *_t1 position (metres), t ∈ [0, settings.t_max]; parallel and
/// degenerate edges are handled. Returns settings.t_max when the distance stays above
/// ξ = settings.min_distance on the whole interval; otherwise toi ∈ [0, t_max), strictly before
/// the first contact, with distance ≥ ξ + s·(d₀ − ξ) at toi (toi = 0 when d₀ ≤ ξ). Near misses
/// and queries that hit settings.max_iterations are reported the same way (false positives);
/// a contact is never missed.
double edge_edge_toi(const Eigen::Vector3d& ea0_t0, const Eigen::Vector3d& ea1_t0,
                     const Eigen::Vector3d& eb0_t0, const Eigen::Vector3d& eb1_t0,
                     const Eigen::Vector3d& ea0_t1, const Eigen::Vector3d& ea1_t1,
                     const Eigen::Vector3d& eb0_t1, const Eigen::Vector3d& eb1_t1,
                     const CcdSettings& settings);

/// True when the edge–edge motion may come into contact in [0, t_max], i.e. when
/// edge_edge_toi(...) < settings.t_max; false means it is certainly contact-free.
bool edge_edge_may_collide(const Eigen::Vector3d& ea0_t0, const Eigen::Vector3d& ea1_t0,
                           const Eigen::Vector3d& eb0_t0, const Eigen::Vector3d& eb1_t0,
                           const Eigen::Vector3d& ea0_t1, const Eigen::Vector3d& ea1_t1,
                           const Eigen::Vector3d& eb0_t1, const Eigen::Vector3d& eb1_t1,
                           const CcdSettings& settings);

}  // namespace stiffsoft::ccd
