// Analytic CCD families of ../shared/validation.md ("CCD"), ε = FLT_EPSILON: every hit must be
// reported, false positives are counted and printed, non-hits far from contact must be free.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cfloat>
#include <cstdio>
#include <random>
#include <stdexcept>

#include <stiffsoft/coupling/ccd/ccd.hpp>
#include <stiffsoft/coupling/ccd/additive_ccd.hpp>
#include <stiffsoft/coupling/ccd/distance.hpp>

namespace stiffsoft::ccd {
namespace {

using Eigen::Vector3d;
constexpr double eps = FLT_EPSILON;

/// Distance at time t of a point–triangle motion, in long double.
long double pt_distance(const Vector3d& p0, const Vector3d& p1, const Vector3d (&t0)[3],
                        const Vector3d (&t1)[3], long double t) {
  using V = detail::Vec3<long double>;
  auto at = [t](const Vector3d& a, const Vector3d& b) -> V {
    return (1 - t) * a.cast<long double>() + t * b.cast<long double>();
  };
  return std::sqrt(detail::point_triangle_distance_squared<long double>(
      at(p0, p1), at(t0[0], t1[0]), at(t0[1], t1[1]), at(t0[2], t1[2])));
}

TEST(CcdAnalytic, PointTriangleFamilyReportsEveryHit) {
  const double values[] = {-1, 0, 0.5 - eps, 0.5, 0.5 + eps, 1, 2};
  const CcdSettings settings;
  int cases = 0, hits = 0, false_positives = 0;
  for (double z0 : {0.0, -1.0}) {
    for (double a : values) {
      for (double b : values) {
        for (double delta : {-eps, 0.0, eps}) {
          const Vector3d p0(0, 1, z0), p1 = p0 + Vector3d(0, -a, delta);
          const Vector3d t0[3] = {{-1, 0, 1}, {1, 0, 1}, {0, 0, -1}};
          const Vector3d shift(0, b, 0);
          const Vector3d t1[3] = {t0[0] + shift, t0[1] + shift, t0[2] + shift};
          const bool hit = a + b >= 1 && z0 + delta >= -1;
          const double toi = point_triangle_toi(p0, t0[0], t0[1], t0[2], p1, t1[0], t1[1], t1[2],
                                                settings);
          const bool reported = toi < settings.t_max;
          EXPECT_EQ(reported, point_triangle_may_collide(p0, t0[0], t0[1], t0[2], p1, t1[0],
                                                         t1[1], t1[2], settings));
          ++cases;
          hits += hit;
          if (hit) {
            EXPECT_TRUE(reported) << "missed: z0=" << z0 << " a=" << a << " b=" << b
                                  << " delta=" << delta;
            // The contact happens at t = 1/(a + b); toi must come before it with a gap.
            EXPECT_LT(toi, 1 / (a + b));
            EXPECT_GT(pt_distance(p0, p1, t0, t1, toi), 0.0L);
          } else if (reported) {
            ++false_positives;
            std::printf("  point-triangle false positive: z0=%g a=%.9g b=%.9g delta=%.3g toi=%g\n",
                        z0, a, b, delta, toi);
          }
          if (a + b <= 0.5) {
            // The gap never drops below 1 − (a + b) ≥ 0.5 of the initial 1: far from contact.
            EXPECT_FALSE(reported) << "far non-hit reported: a=" << a << " b=" << b;
          }
        }
      }
    }
  }
  std::printf("point-triangle family: %d cases, %d hits, %d false positives\n", cases, hits,
              false_positives);
}

TEST(CcdAnalytic, EdgeEdgeFamilyReportsEveryHit) {
  const double xs[] = {-1 - eps, -1, -1 + eps, -0.5, 0, 0.5, 1 - eps, 1, 1 + eps};
  const double ys[] = {-1, 0, 1 - eps, 1, 1 + eps, 2};
  const CcdSettings settings;
  int cases = 0, hits = 0, false_positives = 0;
  for (double x : xs) {
    for (double y : ys) {
      // Each edge moves by y towards the other: the initial gap of 2 closes when y ≥ 1.
      const Vector3d a0(-1, -1, 0), a1(1, -1, 0), b0(x, 1, -1), b1(x, 1, 1);
      const Vector3d up(0, y, 0);
      const double toi =
          edge_edge_toi(a0, a1, b0, b1, a0 + up, a1 + up, b0 - up, b1 - up, settings);
      const bool reported = toi < settings.t_max;
      EXPECT_EQ(reported,
                edge_edge_may_collide(a0, a1, b0, b1, a0 + up, a1 + up, b0 - up, b1 - up, settings));
      const bool hit = y >= 1 && std::abs(x) <= 1;
      ++cases;
      hits += hit;
      if (hit) {
        EXPECT_TRUE(reported) << "missed: x=" << x << " y=" << y;
        EXPECT_LT(toi, 1 / y);
        EXPECT_GT(2 - 2 * toi * y, 0);  // the y gap at toi, exact for this family
      } else if (reported) {
        ++false_positives;
        std::printf("  edge-edge false positive: x=%.9g y=%.9g toi=%g\n", x, y, toi);
      }
      if (y <= 0.5) {
        EXPECT_FALSE(reported) << "far non-hit reported: x=" << x << " y=" << y;
      }
    }
  }
  std::printf("edge-edge family: %d cases, %d hits, %d false positives\n", cases, hits,
              false_positives);
}

TEST(CcdAnalytic, StaticPointAgainstRisingTriangle) {
  const CcdSettings settings;
  int false_positives = 0;
  for (double q : {-eps, 0.0, eps}) {
    const Vector3d p(0, q, 0);
    const Vector3d t0(0, 0, 0), t1(0, 1, 0), t2(1, 0, 0), lift(0, 0, 1);
    const bool reported =
        point_triangle_may_collide(p, t0, t1, t2, p, t0 + lift, t1 + lift, t2 + lift, settings);
    if (q >= 0) {
      EXPECT_TRUE(reported) << "missed: q=" << q;
    } else if (reported) {
      ++false_positives;
      std::printf("  static point false positive: q=%.3g\n", q);
    }
  }
  std::printf("static point family: 3 cases, 2 hits, %d false positives\n", false_positives);
}

TEST(CcdAnalytic, MinDistanceCountsAsContactAndTheGapIsKept) {
  // A point falls from y = 1 towards the plane of a triangle and stops at y = 0.4 > 0.
  const Vector3d p0(0, 1, 0), p1(0, 0.4, 0);
  const Vector3d t0[3] = {{-1, 0, 1}, {1, 0, 1}, {0, 0, -1}};
  CcdSettings settings;
  EXPECT_FALSE(point_triangle_may_collide(p0, t0[0], t0[1], t0[2], p1, t0[0], t0[1], t0[2],
                                          settings));
  settings.min_distance = 0.5;
  const double toi =
      point_triangle_toi(p0, t0[0], t0[1], t0[2], p1, t0[0], t0[1], t0[2], settings);
  ASSERT_LT(toi, settings.t_max);
  // Distance 1 − 0.6 t must keep ξ + s (d₀ − ξ) = 0.5 + 0.1·0.5 at toi, and contact (0.5) comes
  // at t = 5/6.
  EXPECT_LT(toi, 5.0 / 6.0);
  EXPECT_GE(1 - 0.6 * toi, 0.55 * (1 - 1e-12));
  // t_max limits the search: the contact at 5/6 is outside [0, 0.5].
  settings.t_max = 0.5;
  EXPECT_EQ(point_triangle_toi(p0, t0[0], t0[1], t0[2], p1, t0[0], t0[1], t0[2], settings), 0.5);
}

TEST(CcdAnalytic, InitialContactGivesZero) {
  const Vector3d a0(0, 0, 0), a1(1, 0, 0), b0(0.5, 0, -1), b1(0.5, 0, 1), up(0, 1, 0);
  EXPECT_EQ(edge_edge_toi(a0, a1, b0, b1, a0 + up, a1 + up, b0, b1, CcdSettings{}), 0.0);
}

TEST(CcdAnalytic, ParallelSlidingEdgesAreFree) {
  // Parallel edges 1e-3 apart sliding along each other never touch.
  const Vector3d a0(0, 0, 0), a1(1, 0, 0), b0(0, 1e-3, 0), b1(1, 1e-3, 0), slide(0.5, 0, 0);
  EXPECT_FALSE(edge_edge_may_collide(a0, a1, b0, b1, a0 + slide, a1 + slide, b0 - slide,
                                     b1 - slide, CcdSettings{}));
  // The same edges closing the gap collide.
  const Vector3d down(0, -2e-3, 0);
  EXPECT_TRUE(edge_edge_may_collide(a0, a1, b0, b1, a0, a1, b0 + down, b1 + down, CcdSettings{}));
}

TEST(CcdAnalytic, IterationCapReportsCollisionAtSafeTime) {
  // A tiny gap with a large sliding motion needs many ACCD steps; a cap of 3 must answer
  // "may collide" with a time that is still collision-free.
  // The triangle is tilted so that the bounding boxes overlap and the AABB filter cannot decide;
  // the point slides parallel to its plane, 1e-4 above it.
  const Vector3d p0(0.1, 2e-4, 0.1), p1(0.8, 9e-4, 0.1);
  const Vector3d t0(0, 0, 0), t1(0, 0, 1), t2(1, 1e-3, 0);
  CcdSettings settings;
  settings.max_iterations = 3;
  const double toi = point_triangle_toi(p0, t0, t1, t2, p1, t0, t1, t2, settings);
  EXPECT_LT(toi, settings.t_max);
  EXPECT_GT(toi, 0.0);
  settings.max_iterations = 1000000;
  EXPECT_EQ(point_triangle_toi(p0, t0, t1, t2, p1, t0, t1, t2, settings), settings.t_max);
}

TEST(CcdAnalytic, LowerBoundShortcutGivesTheSameTimesBitForBit) {
  // point_triangle_toi / edge_edge_toi decide with a cheap lower bound of d₀ whether the first
  // step reaches t_max; ACCD without it (a zero bound) must give the same time in every query:
  // near-contact motions, both slow (most end in the shortcut) and fast (most do not).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto point = [&](double scale) -> Vector3d { return Vector3d(u(rng), u(rng), u(rng)) * scale; };
  const auto no_bound = [](const detail::Stencil&) { return 0.0; };
  int shortcut_candidates = 0;
  for (int k = 0; k < 20000; ++k) {
    const double reach = k % 2 ? 1e-4 : 3e-3;  // motion of each vertex over the step
    detail::Stencil x0, x1;
    x0[0] = point(0.1);
    x0[1] = point(0.1);
    x0[2] = point(0.1);
    x0[3] = point(0.1);
    // Bring the second primitive within about 2e-3 of the first (a pile's near contacts).
    const Vector3d shift = x0[1] - x0[2] + point(2e-3);
    for (int i = 2; i < 4; ++i) x0[i] += shift;
    for (int i = 0; i < 4; ++i) x1[i] = x0[i] + point(reach);
    CcdSettings s;
    s.t_max = k % 3 ? 1.0 : 0.5;
    const double pt = point_triangle_toi(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1], x1[2], x1[3], s);
    const double pt_plain = detail::additive_ccd<1>(x0, x1, s, [](const detail::Stencil& x) {
      return detail::point_triangle_distance_squared<double>(x[0], x[1], x[2], x[3]); }, no_bound);
    const double ee = edge_edge_toi(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1], x1[2], x1[3], s);
    const double ee_plain = detail::additive_ccd<2>(x0, x1, s, [](const detail::Stencil& x) {
      return detail::segment_segment_distance_squared<double>(x[0], x[1], x[2], x[3]); }, no_bound);
    ASSERT_EQ(pt, pt_plain) << "query " << k;
    ASSERT_EQ(ee, ee_plain) << "query " << k;
    shortcut_candidates += (pt == s.t_max) + (ee == s.t_max);
  }
  EXPECT_GT(shortcut_candidates, 1000);  // the shortcut's case was exercised
  // Head-on approaches whose first step ends anywhere in [0, 2] t_max: the shortcut must
  // leave every time that ends before t_max alone.
  const Vector3d n(0.1, 1, -0.2), t0(-1, 0, -1), t1(1, 0.2, -1), t2(0, -0.1, 1);
  for (int k = 1; k <= 400; ++k) {
    const double f = 0.01 * k;  // approach over the step, in units of the initial gap
    const detail::Stencil pt0{Vector3d(0, 1e-3, 0), t0, t1, t2};
    detail::Stencil pt1 = pt0;
    pt1[0] -= f * 1e-3 * n.normalized();
    const detail::Stencil ee0{Vector3d(-1, 1e-3, 0.1), Vector3d(1, 1e-3, -0.1), Vector3d(0.1, 0, -1), Vector3d(-0.1, 0, 1)};
    detail::Stencil ee1 = ee0;
    ee1[0].y() -= f * 1e-3;
    ee1[1].y() -= f * 1e-3;
    const CcdSettings s;
    EXPECT_EQ(point_triangle_toi(pt0[0], pt0[1], pt0[2], pt0[3], pt1[0], pt1[1], pt1[2], pt1[3], s),
              detail::additive_ccd<1>(pt0, pt1, s, [](const detail::Stencil& x) {
                return detail::point_triangle_distance_squared<double>(x[0], x[1], x[2], x[3]); }, no_bound))
        << "f = " << f;
    EXPECT_EQ(edge_edge_toi(ee0[0], ee0[1], ee0[2], ee0[3], ee1[0], ee1[1], ee1[2], ee1[3], s),
              detail::additive_ccd<2>(ee0, ee1, s, [](const detail::Stencil& x) {
                return detail::segment_segment_distance_squared<double>(x[0], x[1], x[2], x[3]); }, no_bound))
        << "f = " << f;
  }
}

TEST(CcdAnalytic, InvalidSettingsThrow) {
  const Vector3d z = Vector3d::Zero(), x = Vector3d::UnitX(), y = Vector3d::UnitY();
  for (auto change : {+[](CcdSettings& s) { s.tolerance = 0; },
                      +[](CcdSettings& s) { s.tolerance = 1; },
                      +[](CcdSettings& s) { s.min_distance = -1; },
                      +[](CcdSettings& s) { s.max_iterations = 0; },
                      +[](CcdSettings& s) { s.t_max = 1.5; }}) {
    CcdSettings settings;
    change(settings);
    EXPECT_THROW(edge_edge_toi(z, x, y, x + y, z, x, y, x + y, settings), std::invalid_argument);
  }
}

}  // namespace
}  // namespace stiffsoft::ccd
