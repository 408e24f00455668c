#include <stiffsoft/meshing/mass_moments.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include <stiffsoft/meshing/primitive.hpp>

namespace stiffsoft {
namespace {

SurfaceMesh box(const Eigen::Vector3d& extents) {
  PrimitiveShape s;
  s.type = PrimitiveShape::Type::Box;
  s.extents = extents;
  return make_primitive(s);
}

SurfaceMesh sphere(double r, int n) {
  PrimitiveShape s;
  s.type = PrimitiveShape::Type::Sphere;
  s.radius = r;
  s.resolution = n;
  return make_primitive(s);
}

TEST(MassMoments, BoxIsExact) {
  const Eigen::Vector3d e(1.0, 2.0, 3.0);
  const MassMoments m = mass_moments(box(e));
  const double V = e.prod();
  EXPECT_NEAR(m.volume, V, 1e-12);
  EXPECT_LT(m.first.norm(), 1e-12);
  // \int x_i^2 dV = V e_i^2 / 12 for a centred box; off-diagonals vanish.
  Eigen::Matrix3d expected = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) expected(i, i) = V * e[i] * e[i] / 12.0;
  EXPECT_LT((m.second - expected).cwiseAbs().maxCoeff(), 1e-12) << m.second;
}

TEST(MassMoments, TransformLikeMomentsOfARigidMotion) {
  const SurfaceMesh b = box({0.5, 1.5, 2.0});
  const MassMoments m0 = mass_moments(b);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.3, -1.2, 2.5);
  SurfaceMesh moved = b;
  for (Eigen::Index i = 0; i < b.V.rows(); ++i) moved.V.row(i) = (R * b.V.row(i).transpose() + t).transpose();
  const MassMoments m = mass_moments(moved);
  // x' = R x + t: \int x' = R f + V t, \int x' x'^T = R S R^T + R f t^T + t (R f)^T + V t t^T.
  const Eigen::Vector3d f = R * m0.first;
  const Eigen::Matrix3d S =
      R * m0.second * R.transpose() + f * t.transpose() + t * f.transpose() + m0.volume * t * t.transpose();
  EXPECT_NEAR(m.volume, m0.volume, 1e-12);
  EXPECT_LT((m.first - (f + m0.volume * t)).norm(), 1e-12);
  EXPECT_LT((m.second - S).cwiseAbs().maxCoeff(), 1e-12) << m.second << "\nvs\n" << S;
  EXPECT_LT((m.second - m.second.transpose()).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(MassMoments, InvertedSurfaceHasNegativeVolume) {
  SurfaceMesh b = box({1.0, 1.0, 1.0});
  b.F.col(1).swap(b.F.col(2));
  EXPECT_NEAR(mass_moments(b).volume, -1.0, 1e-14);
}

// The UV sphere's polyhedron is a stack of pyramid frusta (aligned regular n-gons on rings of radius
// ρ_i at heights y_i), so its volume is Σ h/3 (A_i + A_{i+1} + √(A_i A_{i+1})), A = (n/2) ρ² sin(2π/n).
double uv_sphere_volume(double r, int n) {
  const int rings = std::max(2, n / 2);
  const double k = 0.5 * n * std::sin(2.0 * std::numbers::pi / n);
  double V = 0.0;
  for (int i = 0; i < rings; ++i) {
    const double t0 = std::numbers::pi * i / rings, t1 = std::numbers::pi * (i + 1) / rings;
    const double rho0 = r * std::sin(t0), rho1 = r * std::sin(t1);
    const double h = r * (std::cos(t0) - std::cos(t1));
    V += h / 3.0 * k * (rho0 * rho0 + rho1 * rho1 + rho0 * rho1);
  }
  return V;
}

TEST(MassMoments, SphereVolumeMatchesThePolyhedronExactly) {
  for (int n : {4, 9, 16, 64}) {
    const double r = 0.7;
    const MassMoments m = mass_moments(sphere(r, n));
    EXPECT_NEAR(m.volume, uv_sphere_volume(r, n), 1e-13) << n;
    EXPECT_LT(m.first.norm(), 1e-14) << n;
  }
}

TEST(MassMoments, SphereSecondMomentConvergesToTheBall) {
  // \int x x^T dV = (4/15) π r^5 I for a ball. The UV sphere is convex and inscribed, so it lies
  // between the ball of radius r and the ball of radius d_min (smallest distance from the centre to a
  // face plane); moments of nested solids are ordered, so V and each diagonal entry of \int x x^T are
  // sandwiched between the two balls' values. The error must also shrink as O(1/n²): each doubling
  // of n must divide it by more than 3.5 (second order gives 4).
  const double r = 1.3;
  const double ball_second = 4.0 / 15.0 * std::numbers::pi * std::pow(r, 5);
  const double ball_volume = 4.0 / 3.0 * std::numbers::pi * std::pow(r, 3);
  double previous = 0.0;
  for (int n : {16, 32, 64, 128}) {
    const SurfaceMesh s = sphere(r, n);
    double d_min = r;
    for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
      const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
      d_min = std::min(d_min, (b - a).cross(c - a).normalized().dot(a));
    }
    const double q = d_min / r;
    const MassMoments m = mass_moments(s);
    EXPECT_LE(m.volume, ball_volume) << n;
    EXPECT_GE(m.volume, std::pow(q, 3) * ball_volume) << n;
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(m.second(i, i), ball_second) << n;
      EXPECT_GE(m.second(i, i), std::pow(q, 5) * ball_second) << n;
      for (int j = 0; j < 3; ++j)
        if (j != i) {
          EXPECT_NEAR(m.second(i, j), 0.0, 1e-14) << n;  // mirror symmetry
        }
    }
    const double error = (m.second - ball_second * Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() / ball_second;
    if (previous > 0.0) {
      EXPECT_GT(previous / error, 3.5) << n;
    }
    previous = error;
  }
  EXPECT_LT(previous, 2e-3);  // n = 128
}

}  // namespace
}  // namespace stiffsoft
