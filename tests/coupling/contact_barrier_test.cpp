/// Barrier, edge–edge mollifier, barrier potential of one stencil and PSD projection:
/// derivatives against finite differences for every pair (mollified and segment-distance
/// edge–edge included), finite numbers on degenerate inputs, projected Hessians PSD and equal
/// to the projection of the whole matrix (the ≤ 5-dimensional one included, on degenerate pairs).

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cstdio>
#include <random>

#include <stiffsoft/coupling/contact/barrier.hpp>
#include <stiffsoft/coupling/contact/barrier_potential.hpp>
#include <stiffsoft/coupling/contact/edge_edge_mollifier.hpp>
#include <stiffsoft/coupling/contact/projected_barrier_hessian.hpp>
#include <stiffsoft/coupling/contact/psd_projection.hpp>
#include "contact_stencils.hpp"
#include "finite_differences.hpp"

namespace stiffsoft::contact {
namespace {

using Eigen::Vector3d;
using testing::fd_gradient;
using testing::fd_jacobian;
using testing::min_eigenvalue;
using testing::relative_error;

constexpr PrimitivePair kAllPairs[] = {PrimitivePair::VertexVertex, PrimitivePair::EdgeVertex,
                                       PrimitivePair::EdgeEdge, PrimitivePair::FaceVertex};

using test_stencils::random_unit;
using test_stencils::stencil_at_distance;

/// The nearest PSD matrix to the whole 12×12 H, by a full eigen-decomposition: the reference
/// the barrier's projection in the translation complement must equal.
Matrix12d projected_whole(const Matrix12d& H) {
  const Eigen::SelfAdjointEigenSolver<Matrix12d> es(H);
  return es.eigenvectors() * es.eigenvalues().cwiseMax(0.0).asDiagonal() * es.eigenvectors().transpose();
}

/// Nearly parallel edges (angle θ with sin²θ < 1e-3, i.e. below the mollifier threshold)
/// crossing at their interiors, at distance d: an EE stencil whose line distance is the true one.
Vector12d nearly_parallel_crossing_edges(double d, double angle, std::mt19937& rng) {
  const Vector3d n = random_unit(rng);
  Vector3d t = random_unit(rng);
  t = (t - t.dot(n) * n).normalized();
  const Vector3d b = n.cross(t);
  const Vector3d db = std::cos(angle) * t + std::sin(angle) * b;
  return pack_stencil(d * n - 0.45 * t, d * n + 0.55 * t, -0.6 * db, 0.4 * db);
}

/// Nearly parallel edges that do not overlap (eb starts past ea1, sideways by 0.02), so the
/// true distance is an endpoint type and exceeds the line distance d.
Vector12d nearly_parallel_staggered_edges(double d, double angle, std::mt19937& rng) {
  const Vector3d n = random_unit(rng);
  Vector3d t = random_unit(rng);
  t = (t - t.dot(n) * n).normalized();
  const Vector3d b = n.cross(t);
  const Vector3d db = std::cos(angle) * t + std::sin(angle) * b;
  return pack_stencil(d * n, d * n + t, 1.03 * t + 0.02 * b, 1.03 * t + 0.02 * b + 0.9 * db);
}

TEST(Barrier, DerivativesMatchFiniteDifferences) {
  const double dhat = 1e-2, s_hat = dhat * dhat;
  for (double frac : {1e-6, 1e-3, 0.01, 0.1, 0.3, 0.5, 0.9, 0.999}) {
    // Step relative to the distance from both ends of (0, ŝ): near ŝ, b' ~ (ŝ − s)² is tiny.
    const double s = frac * s_hat, h = 1e-6 * std::min(s, s_hat - s);
    const double fd1 = (barrier(s + h, dhat) - barrier(s - h, dhat)) / (2 * h);
    const double fd2 = (barrier_first_derivative(s + h, dhat) - barrier_first_derivative(s - h, dhat)) / (2 * h);
    EXPECT_NEAR(barrier_first_derivative(s, dhat), fd1, 1e-7 * std::abs(fd1)) << frac;
    EXPECT_NEAR(barrier_second_derivative(s, dhat), fd2, 1e-7 * std::abs(fd2)) << frac;
    EXPECT_GT(barrier(s, dhat), 0.0);
    EXPECT_LT(barrier_first_derivative(s, dhat), 0.0);
    EXPECT_GT(barrier_second_derivative(s, dhat), 0.0);
  }
}

TEST(Barrier, IsZeroBeyondDhatAndC2AtDhat) {
  const double dhat = 1e-3, s_hat = dhat * dhat;
  EXPECT_EQ(barrier(s_hat, dhat), 0.0);
  EXPECT_EQ(barrier(2 * s_hat, dhat), 0.0);
  EXPECT_EQ(barrier_first_derivative(2 * s_hat, dhat), 0.0);
  EXPECT_EQ(barrier_second_derivative(2 * s_hat, dhat), 0.0);
  // b, b' → 0 and b'' → 0 as s → ŝ from below (b'' ≈ 6 (ŝ − s)/ŝ).
  const double s = s_hat * (1 - 1e-9);
  EXPECT_LT(std::abs(barrier(s, dhat)), 1e-30);
  EXPECT_LT(std::abs(barrier_first_derivative(s, dhat)), 1e-20);
  EXPECT_LT(std::abs(barrier_second_derivative(s, dhat)), 1e-7);
  EXPECT_EQ(barrier(0.0, dhat), std::numeric_limits<double>::infinity());
}

TEST(EdgeEdgeMollifier, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(21);
  double worst_g = 0, worst_h = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double angle = std::pow(10.0, -3.0 + 1.4 * (trial % 8) / 7.0);  // sin²θ from 1e-6 to 1.6e-3
    const Vector12d x = nearly_parallel_crossing_edges(0.01, angle, rng);
    const double eps_x = edge_edge_mollifier_threshold(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6),
                                                       x.segment<3>(9));
    const auto f = [&](const Eigen::VectorXd& y) { return edge_edge_mollifier(Vector12d(y), eps_x); };
    const auto g = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd {
      return edge_edge_mollifier_gradient(Vector12d(y), eps_x);
    };
    if (edge_edge_cross_squared_norm(x) >= eps_x) {
      EXPECT_EQ(edge_edge_mollifier(x, eps_x), 1.0);
      continue;
    }
    worst_g = std::max(worst_g, relative_error(edge_edge_mollifier_gradient(x, eps_x), fd_gradient(f, x, 1e-7)));
    worst_h = std::max(worst_h, relative_error(edge_edge_mollifier_hessian(x, eps_x), fd_jacobian(g, x, 1e-7)));
  }
  std::printf("    mollifier: worst gradient error %.2e, Hessian error %.2e\n", worst_g, worst_h);
  EXPECT_LT(worst_g, 1e-6);
  EXPECT_LT(worst_h, 1e-6);
  // The cross-norm Hessian itself, on generic edges.
  for (int trial = 0; trial < 50; ++trial) {
    const Vector12d x = stencil_at_distance(PrimitivePair::EdgeEdge, 0.3, rng);
    const auto g = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd {
      return edge_edge_cross_squared_norm_gradient(Vector12d(y));
    };
    const auto f = [&](const Eigen::VectorXd& y) { return edge_edge_cross_squared_norm(Vector12d(y)); };
    EXPECT_LT(relative_error(edge_edge_cross_squared_norm_gradient(x), fd_gradient(f, x)), 1e-8);
    EXPECT_LT(relative_error(edge_edge_cross_squared_norm_hessian(x), fd_jacobian(g, x)), 1e-8);
  }
}

TEST(EdgeEdgeMollifier, IsOneAboveThresholdAndZeroForParallelEdges) {
  const Vector3d o(0, 0, 0), ex(1, 0, 0), ey(0, 1, 0), ez(0, 0, 1);
  const double eps_x = edge_edge_mollifier_threshold(o, ex, o, ey);
  EXPECT_DOUBLE_EQ(eps_x, 1e-3);
  EXPECT_EQ(edge_edge_mollifier(pack_stencil(o, ex, ez, ez + ey), eps_x), 1.0);
  EXPECT_EQ(edge_edge_mollifier(pack_stencil(o, ex, ez, ez + ex), eps_x), 0.0);
  // m̃ is C¹ at ε_x: value 1 and slope 0 from below.
  EXPECT_NEAR(mollifier_of_cross(eps_x * (1 - 1e-8), eps_x), 1.0, 1e-15);
}

/// Runs value/gradient/Hessian FD checks of the barrier potential for one stencil.
struct FdResult {
  double grad_error, hess_error;
};
FdResult barrier_potential_fd(const Stencil& s, const Vector12d& x, double dhat, double h) {
  const auto f = [&](const Eigen::VectorXd& y) { return barrier_potential(s, Vector12d(y), dhat); };
  const auto g = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd {
    return barrier_potential_gradient(s, Vector12d(y), dhat);
  };
  return {relative_error(barrier_potential_gradient(s, x, dhat), fd_gradient(f, x, h)),
          relative_error(barrier_potential_hessian(s, x, dhat, false), fd_jacobian(g, x, h))};
}

TEST(BarrierPotential, GradientAndHessianMatchFiniteDifferencesForEveryPair) {
  const double dhat = 0.1;
  for (PrimitivePair kind : kAllPairs) {
    std::mt19937 rng(300 + int(kind));
    double worst_g = 0, worst_h = 0;
    for (int trial = 0; trial < 200; ++trial) {
      const double d = dhat * (0.05 + 0.9 * (trial % 10) / 9.0);
      const Vector12d x = stencil_at_distance(kind, d, rng);
      ASSERT_NEAR(squared_distance(kind, x), d * d, 1e-12);
      const FdResult r = barrier_potential_fd({kind}, x, dhat, 1e-5 * d);
      worst_g = std::max(worst_g, r.grad_error);
      worst_h = std::max(worst_h, r.hess_error);
    }
    std::printf("    barrier potential kind %d: worst gradient error %.2e, Hessian error %.2e\n", int(kind),
                worst_g, worst_h);
    EXPECT_LT(worst_g, 1e-6) << "kind " << int(kind);
    EXPECT_LT(worst_h, 1e-5) << "kind " << int(kind);
  }
}

TEST(BarrierPotential, MollifiedNearlyParallelEdgesMatchFiniteDifferences) {
  const double dhat = 0.1;
  std::mt19937 rng(31);
  double worst_g = 0, worst_h = 0;
  int mollified = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double angle = std::pow(10.0, -2.5 + 0.9 * (trial % 6) / 5.0);  // sin²θ 1e-5 .. 6e-4
    const double d = dhat * (0.1 + 0.8 * (trial % 5) / 4.0);
    const Vector12d x = nearly_parallel_crossing_edges(d, angle, rng);
    const Stencil s{PrimitivePair::EdgeEdge,
                    edge_edge_mollifier_threshold(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), x.segment<3>(9))};
    ASSERT_LT(edge_edge_cross_squared_norm(x), s.eps_x);
    ++mollified;
    // The line distance is the true one here: both closest points are interior.
    ASSERT_EQ(classify_edge_edge_stencil(x).kind, PrimitivePair::EdgeEdge);
    const FdResult r = barrier_potential_fd(s, x, dhat, 1e-7);
    worst_g = std::max(worst_g, r.grad_error);
    worst_h = std::max(worst_h, r.hess_error);
  }
  EXPECT_EQ(mollified, 200);
  std::printf("    mollified EE (line distance): worst gradient error %.2e, Hessian error %.2e\n", worst_g, worst_h);
  EXPECT_LT(worst_g, 1e-6);
  EXPECT_LT(worst_h, 1e-5);
}

TEST(BarrierPotential, SegmentDistanceStencilsUseTheTrueDistanceAndMatchFiniteDifferences) {
  const double dhat = 0.1;
  std::mt19937 rng(32);
  double worst_g = 0, worst_h = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double angle = std::pow(10.0, -2.5 + 0.9 * (trial % 6) / 5.0);
    const double d = dhat * (0.1 + 0.8 * (trial % 5) / 4.0);
    const Vector12d x = nearly_parallel_staggered_edges(0.6 * d, angle, rng);
    const Stencil s{PrimitivePair::EdgeEdge,
                    edge_edge_mollifier_threshold(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), x.segment<3>(9)),
                    true};
    ASSERT_LT(edge_edge_cross_squared_norm(x), s.eps_x);
    ASSERT_NE(classify_edge_edge_stencil(x).kind, PrimitivePair::EdgeEdge);
    const double exact = segment_segment_squared_distance(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6),
                                                          x.segment<3>(9));
    EXPECT_EQ(stencil_squared_distance(s, x), exact);
    // The line distance differs: it is what an unflagged stencil would (wrongly) use.
    EXPECT_LT(squared_distance(PrimitivePair::EdgeEdge, x), 0.9 * exact);
    const FdResult r = barrier_potential_fd(s, x, dhat, 1e-7);
    worst_g = std::max(worst_g, r.grad_error);
    worst_h = std::max(worst_h, r.hess_error);
  }
  std::printf("    mollified EE (segment distance): worst gradient error %.2e, Hessian error %.2e\n", worst_g, worst_h);
  EXPECT_LT(worst_g, 1e-6);
  EXPECT_LT(worst_h, 1e-5);
}

TEST(BarrierPotential, IsZeroBeyondDhat) {
  std::mt19937 rng(33);
  for (PrimitivePair kind : kAllPairs) {
    const Vector12d x = stencil_at_distance(kind, 0.2, rng);
    EXPECT_EQ(barrier_potential({kind}, x, 0.1), 0.0);
    EXPECT_TRUE(barrier_potential_gradient({kind}, x, 0.1).isZero(0.0));
    EXPECT_TRUE(barrier_potential_hessian({kind}, x, 0.1, true).isZero(0.0));
  }
}

TEST(BarrierPotential, DegenerateInputsGiveFiniteNumbers) {
  std::mt19937 rng(34);
  const double dhat = 1e-3;
  for (PrimitivePair kind : kAllPairs)
    for (double rel : {1e-6, 1e-8, 1e-10, 1e-12}) {
      // Distances of rel·d̂ on primitives of size ~1 (coordinates carry ~1e-16 m of rounding,
      // so the smallest case is a few ulps away from touching).
      const Vector12d x = stencil_at_distance(kind, rel * dhat, rng);
      const double P = barrier_potential({kind}, x, dhat);
      EXPECT_TRUE(std::isfinite(P) && P > 0) << int(kind) << " " << rel;
      EXPECT_TRUE(barrier_potential_gradient({kind}, x, dhat).allFinite()) << int(kind) << " " << rel;
      EXPECT_TRUE(barrier_potential_hessian({kind}, x, dhat, false).allFinite()) << int(kind) << " " << rel;
      EXPECT_TRUE(barrier_potential_hessian({kind}, x, dhat, true).allFinite()) << int(kind) << " " << rel;
    }
  // Exactly parallel mollified edges: the mollifier and its gradient vanish, the potential is 0.
  const Vector3d o(0.3, 0.1, -0.2), ex(1, 0, 0), ey(0, 1, 0);
  for (bool segment : {false, true}) {
    const Stencil s{PrimitivePair::EdgeEdge, 1e-3, segment};
    const Vector12d x = pack_stencil(o, o + ex, o + 0.5 * dhat * ey, o + 0.5 * dhat * ey + 0.8 * ex);
    EXPECT_EQ(barrier_potential(s, x, dhat), 0.0);
    EXPECT_TRUE(barrier_potential_gradient(s, x, dhat).allFinite());
    EXPECT_TRUE(barrier_potential_hessian(s, x, dhat, true).allFinite());
    EXPECT_LT(barrier_potential_gradient(s, x, dhat).norm(), 1e-30);
  }
  // Coincident edges and zero-length edges stay finite in the distance (d = 0 is a contact the
  // solver never lets happen; the barrier itself is +∞ there by definition).
  const Vector12d same = pack_stencil(o, o + ex, o, o + ex);
  EXPECT_TRUE(std::isfinite(stencil_squared_distance({PrimitivePair::EdgeEdge, 1e-3, true}, same)));
  EXPECT_EQ(barrier_potential({PrimitivePair::VertexVertex}, pack_stencil(o, o, o, o), dhat),
            std::numeric_limits<double>::infinity());
}

TEST(BarrierPotential, ProjectedHessianIsPsdAndEqualsTheFullProjection) {
  // b' < 0 times the PSD ∇²d² makes every active barrier Hessian indefinite, so the
  // "PSD stays untouched" property is pinned by ProjectToPsd and the friction tests instead.
  const double dhat = 0.1;
  int indefinite = 0;
  for (PrimitivePair kind : kAllPairs) {
    std::mt19937 rng(400 + int(kind));
    for (int trial = 0; trial < 200; ++trial) {
      const Vector12d x = stencil_at_distance(kind, dhat * (0.05 + 0.9 * (trial % 10) / 9.0), rng);
      const Matrix12d H = barrier_potential_hessian({kind}, x, dhat, false);
      const Matrix12d Hp = barrier_potential_hessian({kind}, x, dhat, true);
      EXPECT_GE(min_eigenvalue(Hp), -1e-10 * Hp.norm());
      // Projecting in the complement of the active vertices' common translations equals
      // projecting the whole 12×12 matrix.
      EXPECT_LT((Hp - projected_whole(H)).norm(), 1e-10 * H.norm());
      // inactive rows and columns stay exactly zero
      const int n = 3 * vertex_count(kind);
      EXPECT_TRUE((Hp.bottomRows(12 - n).array() == 0).all());
      if (min_eigenvalue(H) < 0) ++indefinite;
    }
  }
  std::printf("    barrier Hessians: %d of 800 indefinite before projection\n", indefinite);
  EXPECT_GT(indefinite, 0);
  // Mollified stencils too.
  std::mt19937 rng(41);
  for (int trial = 0; trial < 100; ++trial) {
    const Vector12d x = nearly_parallel_crossing_edges(0.05, 0.01, rng);
    const Matrix12d Hp = barrier_potential_hessian({PrimitivePair::EdgeEdge, 1e-3}, x, dhat, true);
    EXPECT_GE(min_eigenvalue(Hp), -1e-10 * Hp.norm());
    // The mollifier is translation invariant too: projecting in the complement of the common
    // translations equals projecting the whole matrix.
    const Matrix12d H = barrier_potential_hessian({PrimitivePair::EdgeEdge, 1e-3}, x, dhat, false);
    EXPECT_LT((Hp - projected_whole(H)).norm(), 1e-10 * H.norm());
  }
}

TEST(BarrierPotential, EdgePairsFarFromParallelTakeTheUnmollifiedProjection) {
  // An edge–edge stencil carries its mollifier threshold, but where the edges are further from
  // parallel than it the mollifier is 1 and its terms vanish: the Hessian is the unmollified
  // one, and its projection the ≤ 5-dimensional one (not the 9×9 of mollified pairs).
  const double dhat = 0.1;
  std::mt19937 rng(77);
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vector12d x = stencil_at_distance(PrimitivePair::EdgeEdge, dhat * (0.05 + 0.9 * (trial % 10) / 9.0), rng);
    const Stencil mollified{PrimitivePair::EdgeEdge, 1e-6}, plain{PrimitivePair::EdgeEdge};
    if (edge_edge_cross_squared_norm(x) < 1e-6) continue;
    EXPECT_FALSE(mollifier_active(mollified, x));
    const Matrix12d H = barrier_potential_hessian(mollified, x, dhat, false);
    EXPECT_TRUE(H == barrier_potential_hessian(plain, x, dhat, false));
    const Matrix12d Hp = barrier_potential_hessian(mollified, x, dhat, true);
    EXPECT_TRUE(Hp == projected_barrier_hessian(plain, x, dhat));
    EXPECT_LT((Hp - projected_whole(H)).norm(), 1e-10 * H.norm());
    ++compared;
  }
  EXPECT_GT(compared, 150);
  const Vector12d parallel = nearly_parallel_crossing_edges(0.05, 0.01, rng);
  EXPECT_TRUE(mollifier_active({PrimitivePair::EdgeEdge, 1e-3}, parallel));
  EXPECT_FALSE(mollifier_active({PrimitivePair::EdgeEdge}, parallel));
}

TEST(ProjectedBarrierHessian, EqualsTheProjectionInTheTranslationComplementOnHardPairs) {
  // The ≤ 5-dimensional projection against the 9×9 one on the exact Hessian, where the
  // closest-point solve is ill-conditioned: tiny distances, nearly parallel and exactly
  // parallel edges (the Gram matrix's rank-one fallback), a zero-length edge, a sliver face,
  // and unmollified segment-distance stencils (classified sub-pairs, scattered).
  const double dhat = 1e-3;
  const auto expect_same = [dhat](const Stencil& s, const Vector12d& x, const char* what) {
    Matrix12d reference = barrier_potential_hessian(s, x, dhat, false);
    if (!reference.allFinite() || reference.isZero(0.0)) return false;
    project_translation_invariant_to_psd(reference, vertex_count(s.kind));
    const Matrix12d Hp = projected_barrier_hessian(s, x, dhat);
    // Measured: ≤ 4e-15 relative on the random pairs, up to 7e-11 on nearly parallel lines.
    EXPECT_LT((Hp - reference).norm(), 1e-9 * reference.norm()) << what;
    EXPECT_GE(min_eigenvalue(Hp), -1e-10 * Hp.norm()) << what;
    EXPECT_TRUE(Hp.isApprox(Hp.transpose(), 0.0)) << what;  // exactly symmetric
    return true;
  };
  int compared = 0;
  std::mt19937 rng(52);
  for (PrimitivePair kind : kAllPairs)
    for (double rel : {0.9, 0.5, 1e-2, 1e-4, 1e-6})
      for (int trial = 0; trial < 20; ++trial)
        compared += expect_same({kind}, stencil_at_distance(kind, rel * dhat, rng), "random pair");
  const Vector3d o(0.3, 0.1, -0.2), ex(1, 0, 0), ey(0, 1, 0), ez(0, 0, 1);
  for (double angle : {1e-2, 1e-5, 1e-8, 0.0}) {
    const Vector12d crossing = nearly_parallel_crossing_edges(0.4 * dhat, angle, rng);
    compared += expect_same({PrimitivePair::EdgeEdge}, crossing, "nearly parallel lines");
    compared += expect_same({PrimitivePair::EdgeEdge, 0.0, true}, crossing, "crossing segments");
    compared += expect_same({PrimitivePair::EdgeEdge, 0.0, true},
                            nearly_parallel_staggered_edges(0.4 * dhat, angle, rng), "staggered segments");
  }
  compared += expect_same({PrimitivePair::EdgeVertex}, pack_stencil(o + 0.5 * dhat * ey, o, o, o), "zero-length edge");
  compared += expect_same({PrimitivePair::FaceVertex},
                          pack_stencil(o + 0.5 * dhat * ez, o, o + ex, o + 2 * ex + 1e-9 * ey), "sliver face");
  std::printf("    %d hard barrier Hessians compared\n", compared);
  EXPECT_GE(compared, 400);
}

TEST(BarrierPotential, GaussNewtonCoefficientIsTheCurvatureOfTheBarrierInTheDistance) {
  // c(s) = B''(d) / (4 d²) with B(d) = b(d²): compare with central differences of B in d.
  const double dhat = 1e-2;
  for (double frac : {1e-4, 1e-2, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
    const double d = frac * dhat, h = 1e-5 * std::min(d, dhat - d);
    const auto B = [&](double r) { return barrier(r * r, dhat); };
    const double fd = (B(d + h) - 2 * B(d) + B(d - h)) / (h * h);
    const double c = barrier_gauss_newton_coefficient(d * d, dhat);
    EXPECT_GT(c, 0.0) << frac;  // IPC's barrier is convex in d on (0, d̂)
    EXPECT_NEAR(4 * d * d * c, fd, 1e-4 * std::abs(fd)) << frac;
  }
  EXPECT_EQ(barrier_gauss_newton_coefficient(dhat * dhat, dhat), 0.0);
  EXPECT_EQ(barrier_gauss_newton_coefficient(0.0, dhat), std::numeric_limits<double>::infinity());
}

TEST(BarrierPotential, GaussNewtonHessianIsRankOnePsdAlongTheDistanceGradient) {
  const double dhat = 0.1;
  for (PrimitivePair kind : kAllPairs) {
    std::mt19937 rng(700 + int(kind));
    for (int trial = 0; trial < 50; ++trial) {
      const Vector12d x = stencil_at_distance(kind, dhat * (0.05 + 0.9 * (trial % 10) / 9.0), rng);
      const Matrix12d G = barrier_gauss_newton_hessian({kind}, x, dhat);
      EXPECT_GE(min_eigenvalue(G), -1e-12 * G.norm());
      EXPECT_EQ(barrier_newton_hessian({kind}, x, dhat, BarrierHessian::GaussNewton), G);
      EXPECT_EQ(barrier_newton_hessian({kind}, x, dhat, BarrierHessian::Projected),
                barrier_potential_hessian({kind}, x, dhat, true));
      // G = c ∇d² ∇d²ᵀ: G v = 0 for v ⊥ ∇d², and the exact Hessian agrees along ∇d² up to
      // the left-out b' ∇²d² term.
      const Vector12d g = stencil_squared_distance_gradient({kind}, x);
      const double s = stencil_squared_distance({kind}, x);
      Vector12d v = Vector12d::NullaryExpr([&](Eigen::Index) { return std::normal_distribution<double>()(rng); });
      v -= v.dot(g) / g.squaredNorm() * g;
      EXPECT_LT((G * v).norm(), 1e-10 * G.norm() * v.norm());
      const Matrix12d H = barrier_potential_hessian({kind}, x, dhat, false);
      const double left_out = barrier_first_derivative(s, dhat) *
                              (g.dot(stencil_squared_distance_hessian({kind}, x) * g) - g.squaredNorm() * g.squaredNorm() / (2 * s));
      EXPECT_NEAR(g.dot(G * g), g.dot(H * g) - left_out, 1e-9 * std::abs(g.dot(H * g)));
    }
  }
  // Mollified stencils keep the projected Hessian.
  std::mt19937 rng(71);
  const Vector12d x = nearly_parallel_crossing_edges(0.05, 0.01, rng);
  const Stencil mollified{PrimitivePair::EdgeEdge, 1e-3};
  EXPECT_EQ(barrier_newton_hessian(mollified, x, dhat, BarrierHessian::GaussNewton),
            barrier_potential_hessian(mollified, x, dhat, true));
}

TEST(ProjectToPsd, ReturnsPsdMatricesAndKeepsPsdOnesExactly) {
  std::mt19937 rng(51);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    Eigen::Matrix<double, 9, 9> A;
    for (int i = 0; i < 81; ++i) A.data()[i] = n(rng);
    const Eigen::Matrix<double, 9, 9> S = A + A.transpose();
    const Eigen::Matrix<double, 9, 9> Sp = project_to_psd<9>(S);
    EXPECT_GE(min_eigenvalue(Sp), -1e-12 * Sp.norm());
    EXPECT_LT((Sp - Sp.transpose()).norm(), 1e-12 * Sp.norm());
    // projecting twice changes nothing (up to round-off) and PSD inputs come back bit for bit
    EXPECT_LT((project_to_psd<9>(Sp) - Sp).norm(), 1e-12 * Sp.norm());
    const Eigen::Matrix<double, 9, 9> G = A * A.transpose();
    EXPECT_TRUE(project_to_psd<9>(G) == G);
    // the projection is the nearest PSD matrix: it removes exactly the negative eigenvalues
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> es(S);
    EXPECT_NEAR((Sp - S).norm(), es.eigenvalues().cwiseMin(0.0).norm(), 1e-10 * S.norm());
  }
}

}  // namespace
}  // namespace stiffsoft::contact
