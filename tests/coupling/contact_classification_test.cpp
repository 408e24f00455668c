/// Classification of point–triangle and edge–edge candidates: the classified distance is the
/// exact distance (checked against an independent brute-force minimisation), every IPC type
/// is reached, and hand-made configurations give the expected type and local indices.

#include <gtest/gtest.h>

#include <map>
#include <random>

#include <stiffsoft/coupling/contact/distance_classification.hpp>

namespace stiffsoft::contact {
namespace {

using Eigen::Vector3d;

/// Minimum of a convex function on [lo, hi] by ternary search (100 shrinks of 2/3).
template <class F>
double ternary_minimum(F f, double lo, double hi) {
  for (int it = 0; it < 100; ++it) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (f(m1) < f(m2)) hi = m2; else lo = m1;
  }
  return f(0.5 * (lo + hi));
}

/// Brute force: min over the closed triangle of ‖p − t(β₁, β₂)‖², nested ternary searches
/// (min over β₂ of a jointly convex function is convex in β₁).
double brute_point_triangle(const Vector3d& p, const Vector3d& t0, const Vector3d& t1, const Vector3d& t2) {
  return ternary_minimum(
      [&](double b1) {
        return ternary_minimum(
            [&](double b2) { return (p - (t0 + b1 * (t1 - t0) + b2 * (t2 - t0))).squaredNorm(); }, 0.0,
            1.0 - b1);
      },
      0.0, 1.0);
}

/// Brute force: min over s, t ∈ [0, 1] of ‖ea(s) − eb(t)‖², nested ternary searches.
double brute_segment_segment(const Vector3d& a0, const Vector3d& a1, const Vector3d& b0, const Vector3d& b1) {
  return ternary_minimum(
      [&](double s) {
        return ternary_minimum([&](double t) { return ((a0 + s * (a1 - a0)) - (b0 + t * (b1 - b0))).squaredNorm(); },
                               0.0, 1.0);
      },
      0.0, 1.0);
}

Vector3d random_point(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

std::string type_name(const Classified& c) {
  std::string s = c.kind == PrimitivePair::VertexVertex ? "VV" :
                  c.kind == PrimitivePair::EdgeVertex   ? "EV" :
                  c.kind == PrimitivePair::EdgeEdge     ? "EE" : "FV";
  for (int i = 0; i < vertex_count(c.kind); ++i) s += std::to_string(c.local[i]);
  return s;
}

TEST(ClassifyPointTriangle, ClassifiedDistanceEqualsBruteForceDistance) {
  std::mt19937 rng(11);
  std::map<std::string, int> seen;
  for (int trial = 0; trial < 3000; ++trial) {
    // Triangle near the origin, point from a wider box so every feature can be nearest.
    const Vector3d t0 = random_point(rng, 1), t1 = random_point(rng, 1), t2 = random_point(rng, 1);
    const Vector3d p = random_point(rng, 2.5);
    const Classified c = classify_point_triangle(p, t0, t1, t2);
    ++seen[type_name(c)];
    const double brute = brute_point_triangle(p, t0, t1, t2);
    const double classified = squared_distance(c.kind, gather_classified(c, pack_stencil(p, t0, t1, t2)));
    ASSERT_NEAR(classified, brute, 1e-12 * std::max(1.0, brute)) << "trial " << trial << " " << type_name(c);
    EXPECT_EQ(point_triangle_squared_distance(p, t0, t1, t2), classified);
  }
  // All seven IPC point–triangle types (P_T0..2, P_E0..2, P_T) occur.
  for (const char* t : {"VV01", "VV02", "VV03", "EV012", "EV023", "EV031", "FV0123"})
    EXPECT_GT(seen[t], 20) << t;
  EXPECT_EQ(seen.size(), 7u);
}

TEST(ClassifyEdgeEdge, ClassifiedDistanceEqualsBruteForceDistance) {
  std::mt19937 rng(12);
  std::map<std::string, int> seen;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vector3d a0 = random_point(rng, 1), a1 = random_point(rng, 1);
    const Vector3d b0 = random_point(rng, 1), b1 = random_point(rng, 1);
    const Classified c = classify_edge_edge(a0, a1, b0, b1);
    ++seen[type_name(c)];
    const double brute = brute_segment_segment(a0, a1, b0, b1);
    const double classified = squared_distance(c.kind, gather_classified(c, pack_stencil(a0, a1, b0, b1)));
    ASSERT_NEAR(classified, brute, 1e-12 * std::max(1.0, brute)) << "trial " << trial << " " << type_name(c);
    EXPECT_EQ(segment_segment_squared_distance(a0, a1, b0, b1), classified);
  }
  // All nine IPC edge–edge types (EA0_EB0.., EA_EB0.., EA0_EB.., EA_EB) occur.
  for (const char* t : {"VV02", "VV03", "VV12", "VV13", "EV023", "EV123", "EV201", "EV301", "EE0123"})
    EXPECT_GT(seen[t], 20) << t;
  EXPECT_EQ(seen.size(), 9u);
}

TEST(ClassifyEdgeEdge, NearlyParallelAndDegenerateSegmentsGiveTheExactDistance) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 1000; ++trial) {
    const Vector3d a0 = random_point(rng, 1), a1 = random_point(rng, 1);
    // eb is ea shifted, stretched and tilted by an angle down to 1e-12 (or exactly parallel,
    // or shrunk to a point), where the line–line system is singular.
    const double tilt = trial % 4 == 0 ? 0.0 : std::pow(10.0, -12.0 + 10.0 * (trial % 7) / 6.0);
    const double stretch = trial % 5 == 0 ? 0.0 : 0.5 + (trial % 3);
    const Vector3d shift = random_point(rng, 1);
    const Vector3d b0 = a0 + shift;
    const Vector3d b1 = b0 + stretch * (a1 - a0) + tilt * random_point(rng, 1);
    const double brute = brute_segment_segment(a0, a1, b0, b1);
    const double exact = segment_segment_squared_distance(a0, a1, b0, b1);
    ASSERT_TRUE(std::isfinite(exact));
    EXPECT_NEAR(exact, brute, 1e-10 * std::max(1.0, brute)) << "trial " << trial << " tilt " << tilt;
  }
}

/// Calls check(a0, a1, b0, b1) on the segment pairs the lower-bound tests share: 3000 random
/// ones, 1000 nearly parallel (tilts down to 1e-12), parallel, collinear and zero-length ones,
/// a crossing pair and two points.
template <class Check>
void for_bound_test_segments(std::mt19937& rng, const Check& check) {
  for (int trial = 0; trial < 3000; ++trial)
    check(random_point(rng, 1), random_point(rng, 1), random_point(rng, 1), random_point(rng, 1));
  for (int trial = 0; trial < 1000; ++trial) {
    const Vector3d a0 = random_point(rng, 1), a1 = random_point(rng, 1);
    const double tilt = trial % 4 == 0 ? 0.0 : std::pow(10.0, -12.0 + 10.0 * (trial % 7) / 6.0);
    const double stretch = trial % 5 == 0 ? 0.0 : 0.5 + (trial % 3);
    const Vector3d b0 = a0 + (trial % 6 == 0 ? 0.3 * (a1 - a0) : random_point(rng, 1));  // some collinear
    check(a0, a1, b0, b0 + stretch * (a1 - a0) + tilt * random_point(rng, 1));
  }
  check(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, -1, 1e-3), Vector3d(0.5, 1, 1e-3));  // crossing
  check(Vector3d(0, 0, 0), Vector3d(0, 0, 0), Vector3d(1, 1, 1), Vector3d(1, 1, 1));              // two points
}

/// A lower bound of a squared distance: finite, non-negative and at most `exact` (to rounding).
void expect_lower_bound(double bound, double exact, int trial) {
  EXPECT_TRUE(std::isfinite(bound)) << "trial " << trial;
  EXPECT_GE(bound, 0.0) << "trial " << trial;
  EXPECT_LE(bound, exact + 1e-13 * std::max(1.0, exact)) << "trial " << trial;
}

TEST(SegmentDistanceLowerBound, NeverExceedsTheDistanceAndIsUsuallyWithinHalfOfIt) {
  // Random, nearly parallel, collinear, crossing and zero-length segments: the bound is at most
  // the exact squared distance (to rounding).
  std::mt19937 rng(14);
  int tight = 0, trials = 0;
  const auto check = [&](const Vector3d& a0, const Vector3d& a1, const Vector3d& b0, const Vector3d& b1) {
    const double exact = segment_segment_squared_distance(a0, a1, b0, b1);
    const double bound = segment_segment_squared_distance_lower_bound(a0, a1, b0, b1);
    expect_lower_bound(bound, exact, trials);
    tight += bound >= 0.5 * exact;
    ++trials;
  };
  for_bound_test_segments(rng, check);
  // A useful bound, not just 0: most pairs are bounded to within half their distance.
  EXPECT_GT(tight, trials / 2);
}

TEST(LineDistanceLowerBound, NeverExceedsTheDistanceAndIsExactBetweenCrossingInteriors) {
  // Random, nearly parallel (down to 1e-12 rad), parallel, collinear and zero-length segments:
  // the lines' distance is at most the segments' (to rounding), and equal to it when the
  // closest points lie inside both segments.
  std::mt19937 rng(16);
  int trials = 0, interior = 0, bounded = 0;
  const auto check = [&](const Vector3d& a0, const Vector3d& a1, const Vector3d& b0, const Vector3d& b1) {
    const double exact = segment_segment_squared_distance(a0, a1, b0, b1);
    const double bound = line_line_squared_distance_lower_bound(a0, a1, b0, b1);
    expect_lower_bound(bound, exact, trials);
    if (classify_edge_edge(a0, a1, b0, b1).kind == PrimitivePair::EdgeEdge && bound > 0) {
      EXPECT_NEAR(bound, exact, 1e-10 * std::max(1.0, exact)) << "trial " << trials;
      ++interior;
    }
    bounded += bound > 0;
    ++trials;
  };
  for_bound_test_segments(rng, check);
  EXPECT_GT(interior, 100);
  EXPECT_GT(bounded, trials / 2);
}

TEST(PointTriangleDistanceLowerBound, NeverExceedsTheDistanceAndIsExactOverTheTriangle) {
  // Random, sliver, degenerate (collinear, a point) triangles and points in their plane: the
  // plane's distance is at most the exact squared distance (to rounding), and equal to it for
  // points above the triangle's interior.
  std::mt19937 rng(15);
  int trials = 0, above_interior = 0;
  const auto check = [&](const Vector3d& p, const Vector3d& t0, const Vector3d& t1, const Vector3d& t2,
                         bool sliver = false) {
    const double exact = point_triangle_squared_distance(p, t0, t1, t2);
    const double bound = point_triangle_squared_distance_lower_bound(p, t0, t1, t2);
    ASSERT_TRUE(std::isfinite(bound));
    EXPECT_GE(bound, 0.0);
    EXPECT_LE(bound, exact + 1e-13 * std::max(1.0, exact)) << "trial " << trials;
    if (!sliver && classify_point_triangle(p, t0, t1, t2).kind == PrimitivePair::FaceVertex) {
      EXPECT_NEAR(bound, exact, 1e-12 * std::max(1.0, exact)) << "trial " << trials;
      ++above_interior;
    }
    ++trials;
  };
  for (int trial = 0; trial < 3000; ++trial)
    check(random_point(rng, 1), random_point(rng, 1), random_point(rng, 1), random_point(rng, 1));
  for (int trial = 0; trial < 500; ++trial) {
    const Vector3d t0 = random_point(rng, 1), t1 = random_point(rng, 1);
    const double thin = trial % 3 == 0 ? 0.0 : std::pow(10.0, -12.0 + 10.0 * (trial % 5) / 4.0);
    const Vector3d t2 = t0 + 0.4 * (t1 - t0) + thin * random_point(rng, 1);  // sliver or collinear
    check(random_point(rng, 1), t0, t1, t2, true);
    check(t0 + 0.3 * (t1 - t0) + 0.2 * (t2 - t0), t0, t1, t2, true);  // in the plane
    check(random_point(rng, 1), t0, t0, t0, true);                    // a point
  }
  EXPECT_GT(above_interior, 100);
}

TEST(ClassifyPointTriangle, DegenerateTrianglesGiveTheExactDistance) {
  std::mt19937 rng(14);
  for (int trial = 0; trial < 500; ++trial) {
    const Vector3d t0 = random_point(rng, 1), t1 = random_point(rng, 1);
    // collinear (sliver down to 1e-12) or a point
    const double off = trial % 3 == 0 ? 0.0 : std::pow(10.0, -12.0 + 10.0 * (trial % 5) / 4.0);
    const Vector3d t2 = trial % 7 == 0 ? t0 : t0 + 0.7 * (t1 - t0) + off * random_point(rng, 1);
    const Vector3d t1b = trial % 7 == 0 ? t0 : t1;
    const Vector3d p = random_point(rng, 2);
    const double exact = point_triangle_squared_distance(p, t0, t1b, t2);
    ASSERT_TRUE(std::isfinite(exact));
    EXPECT_NEAR(exact, brute_point_triangle(p, t0, t1b, t2), 1e-10) << "trial " << trial;
  }
}

TEST(ClassifyPointTriangle, HandMadeConfigurationsGiveExpectedTypes) {
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  const auto name = [&](const Vector3d& p) { return type_name(classify_point_triangle(p, t0, t1, t2)); };
  EXPECT_EQ(name({0.2, 0.2, 0.5}), "FV0123");
  EXPECT_EQ(name({0.2, 0.2, -0.5}), "FV0123");
  EXPECT_EQ(name({-0.5, -0.5, 0.1}), "VV01");
  EXPECT_EQ(name({1.5, -0.1, 0.1}), "VV02");
  EXPECT_EQ(name({-0.1, 1.5, 0.1}), "VV03");
  EXPECT_EQ(name({0.5, -0.5, 0.1}), "EV012");
  EXPECT_EQ(name({0.8, 0.8, 0.1}), "EV023");
  EXPECT_EQ(name({-0.5, 0.5, 0.1}), "EV031");
}

TEST(ClassifyEdgeEdge, HandMadeConfigurationsGiveExpectedTypes) {
  const Vector3d a0(-1, 0, 0), a1(1, 0, 0);
  const auto name = [&](const Vector3d& b0, const Vector3d& b1) {
    return type_name(classify_edge_edge(a0, a1, b0, b1));
  };
  EXPECT_EQ(name({0, -1, 1}, {0, 1, 1}), "EE0123");             // crossing
  EXPECT_EQ(name({0, 0.5, 1}, {0, 2, 1}), "EV201");             // eb0 over ea's interior
  EXPECT_EQ(name({0, 2, 1}, {0, 0.5, 1}), "EV301");
  EXPECT_EQ(name({-2, -1, 1}, {-2, 1, 1}), "EV023");            // ea0 beside eb's interior
  EXPECT_EQ(name({2, -1, 1}, {2, 1, 1}), "EV123");
  EXPECT_EQ(name({-2, -1, 1}, {-3, -2, 1}), "VV02");
  EXPECT_EQ(name({2, 2, 1}, {2, 1, 1}), "VV13");
  EXPECT_EQ(name({-0.5, 1, 0}, {0.5, 1, 0}), "EV201");          // parallel, overlapping: an endpoint type
}

}  // namespace
}  // namespace stiffsoft::contact
