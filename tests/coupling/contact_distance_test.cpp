/// Squared distances of the four primitive pairs: value against closed forms, gradient and
/// Hessian against finite differences, unused vertices, degenerate inputs.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <random>
#include <vector>

#include <stiffsoft/coupling/contact/squared_distance.hpp>
#include "finite_differences.hpp"

namespace stiffsoft::contact {
namespace {

using Eigen::Vector3d;
using testing::fd_gradient;
using testing::fd_jacobian;
using testing::relative_error;

constexpr PrimitivePair kAllPairs[] = {PrimitivePair::VertexVertex, PrimitivePair::EdgeVertex,
                                       PrimitivePair::EdgeEdge, PrimitivePair::FaceVertex};

Vector3d random_point(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return {u(rng), u(rng), u(rng)};
}

/// Closed-form squared distance, independent of the implementation's least-squares route.
double closed_form_squared_distance(PrimitivePair kind, const Vector12d& x) {
  const Vector3d x0 = x.segment<3>(0), x1 = x.segment<3>(3), x2 = x.segment<3>(6), x3 = x.segment<3>(9);
  switch (kind) {
    case PrimitivePair::VertexVertex: return (x0 - x1).squaredNorm();
    case PrimitivePair::EdgeVertex: return (x0 - x1).cross(x2 - x1).squaredNorm() / (x2 - x1).squaredNorm();
    case PrimitivePair::FaceVertex: {
      const Vector3d n = (x2 - x1).cross(x3 - x1);
      const double h = (x0 - x1).dot(n);
      return h * h / n.squaredNorm();
    }
    case PrimitivePair::EdgeEdge: {
      const Vector3d n = (x1 - x0).cross(x3 - x2);
      const double h = (x0 - x2).dot(n);
      return h * h / n.squaredNorm();
    }
  }
  return 0;
}

/// Random stencil of the given kind, well conditioned: edges ≥ 0.3 long, triangle angles and
/// edge–edge angle bounded away from 0, distance ≥ 0.1. Unused tail entries get garbage.
Vector12d well_conditioned_stencil(PrimitivePair kind, std::mt19937& rng) {
  for (;;) {
    Vector12d x;
    for (int i = 0; i < 4; ++i) x.segment<3>(3 * i) = random_point(rng);
    const Vector3d x0 = x.segment<3>(0), x1 = x.segment<3>(3), x2 = x.segment<3>(6), x3 = x.segment<3>(9);
    bool ok = closed_form_squared_distance(kind, x) > 0.01;
    if (kind == PrimitivePair::EdgeVertex) ok = ok && (x2 - x1).norm() > 0.3;
    if (kind == PrimitivePair::FaceVertex) {
      const double area2 = (x2 - x1).cross(x3 - x1).norm();
      const double longest = std::max({(x2 - x1).norm(), (x3 - x2).norm(), (x1 - x3).norm()});
      ok = ok && area2 > 0.3 * longest * longest;
    }
    if (kind == PrimitivePair::EdgeEdge) {
      const Vector3d a = x1 - x0, b = x3 - x2;
      ok = ok && a.norm() > 0.3 && b.norm() > 0.3 && a.cross(b).norm() > 0.3 * a.norm() * b.norm();
    }
    if (ok) return x;
  }
}

/// Directions spanned by the two primitives (edges, face sides).
std::vector<Vector3d> primitive_directions(PrimitivePair kind, const Vector12d& x) {
  const Vector3d x0 = x.segment<3>(0), x1 = x.segment<3>(3), x2 = x.segment<3>(6), x3 = x.segment<3>(9);
  switch (kind) {
    case PrimitivePair::VertexVertex: return {};
    case PrimitivePair::EdgeVertex: return {x2 - x1};
    case PrimitivePair::FaceVertex: return {x2 - x1, x3 - x1};
    case PrimitivePair::EdgeEdge: return {x1 - x0, x3 - x2};
  }
  return {};
}

TEST(SquaredDistance, MatchesClosedFormForEveryPair) {
  std::mt19937 rng(7);
  for (PrimitivePair kind : kAllPairs)
    for (int trial = 0; trial < 500; ++trial) {
      const Vector12d x = well_conditioned_stencil(kind, rng);
      const double expected = closed_form_squared_distance(kind, x);
      EXPECT_NEAR(squared_distance(kind, x), expected, 1e-12 * std::max(1.0, expected))
          << "kind " << int(kind) << " trial " << trial;
    }
}

TEST(SquaredDistance, ClosestPointsJoinTheTwoPrimitives) {
  std::mt19937 rng(8);
  for (PrimitivePair kind : kAllPairs)
    for (int trial = 0; trial < 100; ++trial) {
      const Vector12d x = well_conditioned_stencil(kind, rng);
      const ClosestPoints cp = closest_points(kind, x);
      // r = Σ c_i x_i, the weights sum to zero (translation invariance) and r is orthogonal to
      // every primitive direction (first-order optimality).
      Vector3d r = Vector3d::Zero();
      for (int i = 0; i < 4; ++i) r += cp.weights[i] * x.segment<3>(3 * i);
      EXPECT_LT((r - cp.r).norm(), 1e-12);
      EXPECT_NEAR(cp.weights.sum(), 0.0, 1e-12);
      for (const Vector3d& dir : primitive_directions(kind, x))
        EXPECT_NEAR(cp.r.dot(dir), 0.0, 1e-12) << "kind " << int(kind);
    }
}

TEST(SquaredDistance, GradientMatchesFiniteDifferences) {
  for (PrimitivePair kind : kAllPairs) {
    std::mt19937 rng(100 + int(kind));
    double worst = 0;
    for (int trial = 0; trial < 300; ++trial) {
      const Vector12d x = well_conditioned_stencil(kind, rng);
      const auto f = [&](const Eigen::VectorXd& y) { return squared_distance(kind, Vector12d(y)); };
      const Eigen::VectorXd fd = fd_gradient(f, x);
      worst = std::max(worst, relative_error(squared_distance_gradient(kind, x), fd));
    }
    std::printf("    squared distance kind %d: worst gradient error %.2e\n", int(kind), worst);
    EXPECT_LT(worst, 1e-7) << "kind " << int(kind);
  }
}

TEST(SquaredDistance, HessianMatchesFiniteDifferencesOfGradient) {
  for (PrimitivePair kind : kAllPairs) {
    std::mt19937 rng(200 + int(kind));
    double worst = 0;
    for (int trial = 0; trial < 300; ++trial) {
      const Vector12d x = well_conditioned_stencil(kind, rng);
      const auto g = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd {
        return squared_distance_gradient(kind, Vector12d(y));
      };
      const Eigen::MatrixXd fd = fd_jacobian(g, x);
      const Matrix12d H = squared_distance_hessian(kind, x);
      worst = std::max(worst, relative_error(H, fd));
      EXPECT_LT((H - H.transpose()).norm(), 1e-12 * H.norm());
    }
    std::printf("    squared distance kind %d: worst Hessian error %.2e\n", int(kind), worst);
    EXPECT_LT(worst, 1e-6) << "kind " << int(kind);
  }
}

TEST(SquaredDistance, UnusedVerticesAreIgnoredAndGetZeroDerivatives) {
  std::mt19937 rng(3);
  for (PrimitivePair kind : {PrimitivePair::VertexVertex, PrimitivePair::EdgeVertex}) {
    const int n = vertex_count(kind);
    const Vector12d x = well_conditioned_stencil(kind, rng);
    Vector12d y = x;
    y.tail(12 - 3 * n).setConstant(1e300);  // garbage must not leak in
    EXPECT_EQ(squared_distance(kind, x), squared_distance(kind, y));
    const Vector12d g = squared_distance_gradient(kind, y);
    const Matrix12d H = squared_distance_hessian(kind, y);
    EXPECT_TRUE((g.tail(12 - 3 * n).array() == 0.0).all());
    EXPECT_TRUE((H.rightCols(12 - 3 * n).array() == 0.0).all());
    EXPECT_TRUE((H.bottomRows(12 - 3 * n).array() == 0.0).all());
  }
}

TEST(SquaredDistance, DegenerateInputsGiveFiniteNumbers) {
  const Vector3d o(0.1, -0.2, 0.3), ex(1, 0, 0), ey(0, 1, 0);
  struct Case {
    PrimitivePair kind;
    Vector12d x;
    double expected;  // known distance², m²
  };
  const Case cases[] = {
      {PrimitivePair::VertexVertex, pack_stencil(o, o, o, o), 0.0},
      {PrimitivePair::EdgeVertex, pack_stencil(o + ey, o, o, o), 1.0},          // zero-length edge
      {PrimitivePair::EdgeVertex, pack_stencil(o, o, o + ex, o), 0.0},          // point on the line
      {PrimitivePair::EdgeEdge, pack_stencil(o, o + ex, o + ey, o + ey + 2 * ex), 1.0},  // parallel
      {PrimitivePair::EdgeEdge, pack_stencil(o, o + ex, o + ey, o + ey + ex + 1e-9 * Vector3d(0, 0, 1)), 1.0},  // sin θ = 1e-9,
      {PrimitivePair::EdgeEdge, pack_stencil(o, o + ex, o, o + ex), 0.0},       // identical edges
      {PrimitivePair::EdgeEdge, pack_stencil(o, o, o + ey, o + ey), 1.0},       // two points
      {PrimitivePair::FaceVertex, pack_stencil(o + ey, o, o + ex, o + 2 * ex), 1.0},  // collinear face
      {PrimitivePair::FaceVertex, pack_stencil(o + ey, o, o, o), 1.0},          // face is a point
      {PrimitivePair::FaceVertex, pack_stencil(o + 1e-12 * ey.cross(ex), o, o + ex, o + ey), 1e-24},
      {PrimitivePair::EdgeEdge, pack_stencil(o, o + ex, o + ey * 1e-12, o + ey * 1e-12 + Vector3d(0, 0, 1)), 1e-24},
  };
  for (const Case& c : cases) {
    const double d2 = squared_distance(c.kind, c.x);
    EXPECT_TRUE(std::isfinite(d2));
    // Coordinates are O(1), so the inputs themselves carry ~1e-16 m of rounding: that, not
    // a relative tolerance, bounds what the distance can resolve.
    EXPECT_NEAR(std::sqrt(d2), std::sqrt(c.expected), 1e-15) << int(c.kind);
    EXPECT_TRUE(squared_distance_gradient(c.kind, c.x).allFinite()) << int(c.kind);
    EXPECT_TRUE(squared_distance_hessian(c.kind, c.x).allFinite()) << int(c.kind);
  }
}

}  // namespace
}  // namespace stiffsoft::contact
