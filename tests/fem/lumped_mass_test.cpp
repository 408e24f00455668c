#include <stiffsoft/libfem/lumped_mass.hpp>

#include <gtest/gtest.h>

#include <random>

#include <stiffsoft/libfem/box_tet_mesh.hpp>

using namespace stiffsoft::fem;

TEST(LumpedMass, SumsToDensityTimesVolume) {
  TetMesh mesh = box_tet_mesh({1.0, 0.1, 0.1}, {10, 2, 2});
  const double rho = 1200;
  const Eigen::VectorXd m = lumped_mass(mesh.X, mesh.T, rho);
  ASSERT_EQ(m.size(), mesh.X.rows());
  EXPECT_NEAR(m.sum(), rho * 1.0 * 0.1 * 0.1, 1e-12 * rho * 0.01);
  EXPECT_GT(m.minCoeff(), 0.0);
  // Node (0,0,0) is a vertex of all 6 tets of its cell and of no other: it gets ρ V_cell / 4.
  EXPECT_NEAR(m[0], rho * (0.1 * 0.05 * 0.05) / 4, 1e-12);
}

TEST(LumpedMass, SumIsExactOnAJitteredMesh) {
  TetMesh mesh = box_tet_mesh({1, 1, 1}, {3, 3, 3});
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (Eigen::Index i = 0; i < mesh.X.rows(); ++i)
    if ((mesh.X.row(i).array() > 1e-9).all() && (mesh.X.row(i).array() < 1 - 1e-9).all())
      mesh.X.row(i) += Eigen::RowVector3d(u(rng), u(rng), u(rng));
  EXPECT_NEAR(lumped_mass(mesh.X, mesh.T, 1000).sum(), 1000.0, 1e-10);
}

TEST(LumpedMass, RejectsNonPositiveDensity) {
  TetMesh mesh = box_tet_mesh({1, 1, 1}, {1, 1, 1});
  EXPECT_THROW(lumped_mass(mesh.X, mesh.T, 0), std::invalid_argument);
  EXPECT_THROW(lumped_mass(mesh.X, mesh.T, -5), std::invalid_argument);
}
