#include <stiffsoft/meshing/tet_quality.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace stiffsoft {
namespace {

TetMesh one_tet(const Eigen::Matrix<double, 4, 3>& x) {
  TetMesh m;
  m.X = x;
  m.T.resize(1, 4);
  m.T << 0, 1, 2, 3;
  return m;
}

TEST(TetQuality, RegularTetHasRadiusRatioOneAndEqualDihedralAngles) {
  Eigen::Matrix<double, 4, 3> x;
  x << 1, 1, 1, -1, 1, -1, 1, -1, -1, -1, -1, 1;  // alternate cube corners, positively ordered
  const TetMesh m = one_tet(x);
  ASSERT_GT(tet_signed_volume(m, 0), 0.0);
  const TetShape s = tet_shape(m, 0);
  const double regular = std::acos(1.0 / 3.0) * 180.0 / std::numbers::pi;  // 70.5288°
  EXPECT_NEAR(s.min_dihedral_angle_deg, regular, 1e-12);
  EXPECT_NEAR(s.max_dihedral_angle_deg, regular, 1e-12);
  EXPECT_NEAR(s.radius_ratio, 1.0, 1e-14);
}

TEST(TetQuality, CornerTetMatchesClosedForms) {
  // (0, e1, e2, e3): right angles at the three edges through the origin, acos(1/√3) at the three
  // edges of the oblique face; r_in = 1/(3 + √3), r_circ = √3/2, so 3 r_in / r_circ = √3 − 1.
  Eigen::Matrix<double, 4, 3> x;
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  const TetMesh m = one_tet(x);
  const TetShape s = tet_shape(m, 0);
  EXPECT_NEAR(s.min_dihedral_angle_deg, std::acos(1.0 / std::sqrt(3.0)) * 180.0 / std::numbers::pi, 1e-12);
  EXPECT_NEAR(s.max_dihedral_angle_deg, 90.0, 1e-12);
  EXPECT_NEAR(s.radius_ratio, std::sqrt(3.0) - 1.0, 1e-14);

  // Scaling and reflecting change nothing.
  TetMesh mirrored = one_tet(-3.0 * x);
  const TetShape t = tet_shape(mirrored, 0);
  EXPECT_NEAR(t.radius_ratio, s.radius_ratio, 1e-14);
  EXPECT_NEAR(t.min_dihedral_angle_deg, s.min_dihedral_angle_deg, 1e-11);
}

TEST(TetQuality, FlatTetHasZeroRatioAndZeroAngle) {
  Eigen::Matrix<double, 4, 3> x;
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;
  const TetShape s = tet_shape(one_tet(x), 0);
  EXPECT_EQ(s.radius_ratio, 0.0);
  EXPECT_NEAR(s.min_dihedral_angle_deg, 0.0, 1e-12);
}

TEST(TetQuality, StatisticsAndSummaryOfTwoTets) {
  TetMesh m;
  m.X.resize(5, 3);
  m.X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  m.T.resize(2, 4);
  m.T << 0, 1, 2, 3, 1, 2, 3, 4;
  const TetQuality q = tet_quality(m);
  EXPECT_EQ(q.num_nodes, 5);
  EXPECT_EQ(q.num_tets, 2);
  EXPECT_DOUBLE_EQ(q.volume, 0.5);
  EXPECT_DOUBLE_EQ(q.min_tet_volume, 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(q.min_edge_length, 1.0);
  EXPECT_DOUBLE_EQ(q.max_edge_length, std::sqrt(2.0));
  // The second tet is regular (edge √2).
  EXPECT_NEAR(q.min_radius_ratio, std::sqrt(3.0) - 1.0, 1e-14);
  EXPECT_NEAR(q.mean_radius_ratio, 0.5 * (std::sqrt(3.0) - 1.0 + 1.0), 1e-14);
  EXPECT_NEAR(q.max_dihedral_angle_deg, 90.0, 1e-12);
  const std::string line = summary(q);
  EXPECT_EQ(line.rfind("5 nodes, 2 tets, volume 0.5 m³", 0), 0u) << line;
  EXPECT_EQ(line.find('\n'), std::string::npos) << line;
}

}  // namespace
}  // namespace stiffsoft
