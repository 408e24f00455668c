#pragma once
/// @file Squared distances between primitives in any configuration (degenerate ones included),
/// private to the CCD. Each is the minimum over candidate features; a "lower" candidate (the
/// distance to a supporting line or plane) is only added when the closest point of that line or
/// plane lies inside the primitive up to a small tolerance. Because a line or plane distance never
/// exceeds the distance to the primitive it contains, a rounding error in that inside test can only
/// make the result smaller, never larger: the CCD stays conservative.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>

namespace stiffsoft::ccd::detail {

/// 3-vector of `Scalar` (double, or long double for reference checks in tests).
template <typename Scalar>
using Vec3 = Eigen::Matrix<Scalar, 3, 1>;

/// Relative slack of the "closest point inside" tests (barycentric / segment parameter units).
template <typename Scalar>
constexpr Scalar inside_slack() {
  return Scalar(1e-9);
}

/// Squared distance (m²) from point p to segment [a, b]; a == b is allowed.
template <typename Scalar>
Scalar point_segment_distance_squared(const Vec3<Scalar>& p, const Vec3<Scalar>& a,
                                      const Vec3<Scalar>& b) {
  const Vec3<Scalar> e = b - a;
  const Vec3<Scalar> r = p - a;
  Scalar d2 = std::min(r.squaredNorm(), (p - b).squaredNorm());
  const Scalar ee = e.squaredNorm();
  if (ee > Scalar(0)) {
    const Scalar s = r.dot(e) / ee;
    if (s >= -inside_slack<Scalar>() && s <= Scalar(1) + inside_slack<Scalar>()) {
      // |e × r|²/|e|² is the distance to the supporting line: never above the segment distance.
      d2 = std::min(d2, e.cross(r).squaredNorm() / ee);
    }
  }
  return d2;
}

/// Squared distance (m²) from point p to triangle (t0, t1, t2); degenerate triangles are allowed.
template <typename Scalar>
Scalar point_triangle_distance_squared(const Vec3<Scalar>& p, const Vec3<Scalar>& t0,
                                       const Vec3<Scalar>& t1, const Vec3<Scalar>& t2) {
  Scalar d2 = std::min({point_segment_distance_squared<Scalar>(p, t0, t1),
                        point_segment_distance_squared<Scalar>(p, t1, t2),
                        point_segment_distance_squared<Scalar>(p, t2, t0)});
  const Vec3<Scalar> n = (t1 - t0).cross(t2 - t0);
  const Scalar nn = n.squaredNorm();
  if (nn > Scalar(0)) {
    // Barycentric coordinates of the projection of p, each as (n · (e_i × (p − t_i))) / |n|².
    const Scalar slack = -inside_slack<Scalar>() * nn;
    if (n.dot((t1 - t0).cross(p - t0)) >= slack && n.dot((t2 - t1).cross(p - t1)) >= slack &&
        n.dot((t0 - t2).cross(p - t2)) >= slack) {
      const Scalar h = n.dot(p - t0);
      d2 = std::min(d2, h * h / nn);
    }
  }
  return d2;
}

/// Squared distance (m²) between segments [a0, a1] and [b0, b1]; parallel and degenerate
/// segments are allowed.
template <typename Scalar>
Scalar segment_segment_distance_squared(const Vec3<Scalar>& a0, const Vec3<Scalar>& a1,
                                        const Vec3<Scalar>& b0, const Vec3<Scalar>& b1) {
  Scalar d2 = std::min({point_segment_distance_squared<Scalar>(a0, b0, b1),
                        point_segment_distance_squared<Scalar>(a1, b0, b1),
                        point_segment_distance_squared<Scalar>(b0, a0, a1),
                        point_segment_distance_squared<Scalar>(b1, a0, a1)});
  const Vec3<Scalar> ea = a1 - a0;
  const Vec3<Scalar> eb = b1 - b0;
  const Vec3<Scalar> n = ea.cross(eb);
  const Scalar nn = n.squaredNorm();
  if (nn > Scalar(0)) {
    // Parameters of the closest points of the two lines, times |n|² (Cramer's rule with the
    // cross product as determinant, which is more accurate than |ea|²|eb|² − (ea·eb)²).
    const Vec3<Scalar> r = b0 - a0;
    const Scalar s_nn = r.cross(eb).dot(n);
    const Scalar t_nn = r.cross(ea).dot(n);
    const Scalar lo = -inside_slack<Scalar>() * nn;
    const Scalar hi = (Scalar(1) + inside_slack<Scalar>()) * nn;
    if (s_nn >= lo && s_nn <= hi && t_nn >= lo && t_nn <= hi) {
      const Scalar h = n.dot(r);
      d2 = std::min(d2, h * h / nn);
    }
  }
  return d2;
}

}  // namespace stiffsoft::ccd::detail
