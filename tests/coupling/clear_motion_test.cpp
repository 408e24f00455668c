// ClearMotion: a pair it calls clear is one whose CCD query returns t_max (the query can be
// skipped), and a pair that can close its gap is never called clear.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>

#include <stiffsoft/coupling/ccd/ccd.hpp>
#include <stiffsoft/coupling/contact/clear_motion.hpp>

namespace stiffsoft {
namespace {

constexpr double kDhat = 1e-3;

/// A point above the triangle (0,0,0), (1,0,0), (0,1,0) at height `height`, over its interior:
/// surface vertices 0 (the point) and 1–3 (the triangle).
Eigen::MatrixX3d point_over_triangle(double height) {
  Eigen::MatrixX3d x(4, 3);
  x << 0.2, 0.3, height, 0, 0, 0, 1, 0, 0, 0, 1, 0;
  return x;
}

/// The face–vertex contact of point_over_triangle(height), active where the point is within d̂.
std::vector<ContactConstraint> face_vertex_contact(double height) {
  ContactConstraint k;
  k.stencil.kind = contact::PrimitivePair::FaceVertex;
  k.vertices = {0, 1, 2, 3};
  k.distance = height;
  return {k};
}

double toi(const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, const ccd::CcdSettings& s) {
  return ccd::point_triangle_toi(x0.row(0).transpose(), x0.row(1).transpose(), x0.row(2).transpose(),
                                 x0.row(3).transpose(), x1.row(0).transpose(), x1.row(1).transpose(),
                                 x1.row(2).transpose(), x1.row(3).transpose(), s);
}

TEST(ClearMotion, CallsAPairClearOnlyWhenItsVerticesMoveTooLittleToCloseItsGap) {
  const ccd::CcdSettings s;
  const Eigen::MatrixX3d x0 = point_over_triangle(0.5 * kDhat);
  Eigen::MatrixX3d small = x0, large = x0;
  small(0, 2) -= 0.05 * kDhat;  // 4 × 0.05 d̂ = 0.2 d̂ < 0.9 × 0.5 d̂: clear
  large(0, 2) -= 1.0 * kDhat;   // passes through the triangle: must be queried
  const ClearMotion clear_small(face_vertex_contact(0.5 * kDhat), x0, small, kDhat, s);
  const ClearMotion clear_large(face_vertex_contact(0.5 * kDhat), x0, large, kDhat, s);
  EXPECT_TRUE(clear_small.is_clear({0, 1, 2, 3}));
  EXPECT_EQ(toi(x0, small, s), s.t_max);
  EXPECT_FALSE(clear_large.is_clear({0, 1, 2, 3}));
  EXPECT_LT(toi(x0, large, s), s.t_max);
}

TEST(ClearMotion, TakesThePairsOutsideTheActiveSetAsAtLeastDhatApart) {
  const ccd::CcdSettings s;
  const Eigen::MatrixX3d x0 = point_over_triangle(3 * kDhat);
  Eigen::MatrixX3d x1 = x0;
  x1(0, 2) -= 0.2 * kDhat;  // 4 × 0.2 d̂ < 0.9 d̂
  const ClearMotion clear(std::vector<ContactConstraint>{}, x0, x1, kDhat, s);
  EXPECT_TRUE(clear.is_clear({0, 1, 2, 3}));
  x1(0, 2) -= 0.1 * kDhat;  // 4 × 0.3 d̂ > 0.9 d̂, though this pair could not close: not clear
  EXPECT_FALSE(ClearMotion(std::vector<ContactConstraint>{}, x0, x1, kDhat, s).is_clear({0, 1, 2, 3}));
}

TEST(ClearMotion, EveryPairItCallsClearIsOneCcdFindsFreeOfContact) {
  // Random moves of every vertex, from a tenth to ten times the gap, heights from 0.01 d̂ to
  // 2 d̂, with t_max below 1 as the edge–edge queries of one island get it.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1), height(0.01 * kDhat, 2 * kDhat), scale(-1, 1);
  int clear_pairs = 0, hits = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    ccd::CcdSettings s;
    s.t_max = trial % 2 ? 1.0 : 0.5;
    const double h = height(rng);
    const Eigen::MatrixX3d x0 = point_over_triangle(h);
    Eigen::MatrixX3d x1 = x0;
    const double reach = h * std::pow(10.0, scale(rng));
    for (int v = 0; v < 4; ++v) x1.row(v) += reach / std::sqrt(3.0) * Eigen::RowVector3d(unit(rng), unit(rng), unit(rng));
    const std::vector<ContactConstraint> active = h < kDhat ? face_vertex_contact(h) : std::vector<ContactConstraint>{};
    const double t = toi(x0, x1, s);
    hits += t < s.t_max;
    if (!ClearMotion(active, x0, x1, kDhat, s).is_clear({0, 1, 2, 3})) continue;
    ++clear_pairs;
    ASSERT_EQ(t, s.t_max) << "trial " << trial;
  }
  EXPECT_GT(clear_pairs, 2000);  // the property was tested on many clear pairs
  EXPECT_GT(hits, 1000);         // and among moves that do reach contact
}

}  // namespace
}  // namespace stiffsoft
