#pragma once
/// @file The Additive CCD loop (Li, Kaufman, Jiang 2021, "Codimensional Incremental Potential
/// Contact", §5, Alg. 1), shared by point–triangle and edge–edge. Private to the CCD: use
/// point_triangle_toi / edge_edge_toi.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <stiffsoft/coupling/ccd/ccd_settings.hpp>

namespace stiffsoft::ccd::detail {

/// The four vertices of a stencil: (p, t0, t1, t2) or (ea0, ea1, eb0, eb1), metres.
using Stencil = std::array<Eigen::Vector3d, 4>;

/// Absolute rounding allowance added to ξ, as a fraction of the largest coordinate magnitude of
/// the query. Positions x(t) = x0 + t·(x1 − x0) are off by a few ε·|x| and the distance formulas
/// by a few ε·|x| times the conditioning of the primitive; 2⁻⁴⁰ ≈ 4096 ε leaves room for a
/// conditioning of several hundred. Every step of ACCD keeps ≥ 10% of the gap, so an error below
/// this allowance cannot let a step pass through contact.
inline constexpr double kRoundingAllowance = 0x1p-40;

/// Additive CCD over the straight-line motion x0 → x1 of one stencil whose first `n_a` vertices
/// form primitive A and the rest primitive B (n_a = 1: point–triangle, n_a = 2: edge–edge).
/// `distance_squared(x)` is the squared distance between the primitives of stencil x, and each
/// of `lower_bounds_squared(x)` a cheaper lower bound of it (0 allowed); tried in order, the
/// first whose step already reaches t_max decides (most queries of a resting pile).
/// Returns settings.t_max when the motion stays farther than ξ in [0, t_max], else a time
/// toi ∈ [0, t_max) at which the primitives are at least ξ + s·(d₀ − ξ) apart (d₀ the initial
/// distance; toi = 0 when d₀ ≤ ξ already).
template <int n_a, typename DistanceSquared, typename... LowerBoundsSquared>
double additive_ccd(const Stencil& x0, const Stencil& x1, const CcdSettings& settings,
                    DistanceSquared&& distance_squared, LowerBoundsSquared&&... lower_bounds_squared) {
  // Scale of the query for the rounding allowance, and the AABB filter: the swept primitive
  // A (resp. B) stays inside the box of its vertices at t = 0 and t = 1, so boxes separated by
  // more than ξ on one axis prove the motion free. Comparisons of the stored coordinates are exact.
  double scale = 0;
  Eigen::Vector3d lo_a = x0[0].cwiseMin(x1[0]), hi_a = x0[0].cwiseMax(x1[0]);
  Eigen::Vector3d lo_b = x0[n_a].cwiseMin(x1[n_a]), hi_b = x0[n_a].cwiseMax(x1[n_a]);
  for (int i = 0; i < 4; ++i) {
    scale = std::max({scale, x0[i].cwiseAbs().maxCoeff(), x1[i].cwiseAbs().maxCoeff()});
    if (i < n_a) {
      lo_a = lo_a.cwiseMin(x0[i]).cwiseMin(x1[i]);
      hi_a = hi_a.cwiseMax(x0[i]).cwiseMax(x1[i]);
    } else {
      lo_b = lo_b.cwiseMin(x0[i]).cwiseMin(x1[i]);
      hi_b = hi_b.cwiseMax(x0[i]).cwiseMax(x1[i]);
    }
  }
  const double xi = settings.min_distance + kRoundingAllowance * scale;
  for (int k = 0; k < 3; ++k) {
    if (hi_a[k] + xi < lo_b[k] || hi_b[k] + xi < lo_a[k]) {
      return settings.t_max;
    }
  }

  // Displacements, less their mean: a common translation does not change the distance, and a
  // smaller l_p allows longer steps (ACCD, Alg. 1 line 2).
  Stencil v;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    v[i] = x1[i] - x0[i];
    mean += v[i];
  }
  mean *= 0.25;
  double max_a = 0, max_b = 0;
  for (int i = 0; i < 4; ++i) {
    const double speed = (v[i] - mean).norm();
    (i < n_a ? max_a : max_b) = std::max(i < n_a ? max_a : max_b, speed);
  }
  // l_p bounds how fast the distance can shrink per unit time: any two points of A and B are
  // convex combinations of the vertices, so their relative speed is at most max_a + max_b.
  const double l_p = (max_a + max_b) * (1 + 1e-12);

  // The first step from a lower bound of d₀, in the same operations as from d₀ below: when it
  // reaches t_max, so does d₀'s (each operation is monotone), and the result is the same. The
  // margin lies far above the bounds' rounding.
  const auto first_step_reaches_t_max = [&](auto&& lower_bound_squared) {
    const double d_low = std::sqrt(lower_bound_squared(x0) / (1 + 1e-6));
    return d_low > xi && (1 - settings.tolerance) * (d_low - xi) / l_p >= settings.t_max;
  };
  if ((first_step_reaches_t_max(lower_bounds_squared) || ...)) {
    return settings.t_max;
  }

  const double d0 = std::sqrt(distance_squared(x0));
  if (d0 <= xi) {
    return 0;  // already in contact (or within the rounding allowance of it)
  }
  if (l_p == 0) {
    return settings.t_max;  // no relative motion
  }
  const double gap = settings.tolerance * (d0 - xi);  // s·(d₀ − ξ): the gap the result keeps

  Stencil x;
  double t = 0;
  double d = d0;
  // The first step may use up (1 − s) of the gap, later ones 0.9 of what is left (Alg. 1).
  double step = (1 - settings.tolerance) * (d0 - xi) / l_p;
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    // Invariant: the motion is farther than ξ on [0, t + step] (d − ξ ≥ l_p·step/0.9 at t).
    const double t_next = t + step;
    if (t_next >= settings.t_max) {
      return settings.t_max;
    }
    for (int i = 0; i < 4; ++i) {
      x[i] = x0[i] + t_next * (x1[i] - x0[i]);
    }
    d = std::sqrt(distance_squared(x));
    if (d - xi < gap) {
      return t;  // closer than the target gap: t is the last time known to keep it
    }
    t = t_next;
    step = 0.9 * (d - xi) / l_p;
  }
  return t;  // iteration cap: report a collision at the last safe time
}

}  // namespace stiffsoft::ccd::detail
