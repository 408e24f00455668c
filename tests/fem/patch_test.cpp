// The patch test (validation.md): a linear-elastic mesh with an affine displacement prescribed on
// its boundary reproduces the uniform strain in every element, to solver precision.
#include <gtest/gtest.h>

#include <random>

#include <stiffsoft/libfem/box_tet_mesh.hpp>
#include <stiffsoft/libfem/elastic_energy.hpp>
#include <stiffsoft/libfem/make_material.hpp>
#include <stiffsoft/libfem/solve_static.hpp>

using namespace stiffsoft::fem;

namespace {
bool on_boundary(const Eigen::RowVector3d& X) {
  return (X.array() < 1e-12).any() || (X.array() > 1 - 1e-12).any();
}
}  // namespace

TEST(PatchTest, AffineBoundaryDisplacementGivesUniformStrainEverywhere) {
  // Unit cube, 4×4×4 cells × 6 tets; the 27 interior nodes jittered by up to 0.15 h per axis so
  // no element is a Kuhn tet any more (h = 0.25 m).
  TetMesh mesh = box_tet_mesh({1, 1, 1}, {4, 4, 4});
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<bool> fixed(mesh.X.rows());
  for (Eigen::Index i = 0; i < mesh.X.rows(); ++i) {
    fixed[i] = on_boundary(mesh.X.row(i));
    if (!fixed[i]) mesh.X.row(i) += 0.15 * 0.25 * Eigen::RowVector3d(u(rng), u(rng), u(rng));
  }
  const ElasticEnergy energy(mesh.X, mesh.T, make_material("linear", 1e7, 0.3));

  // u(X) = G X + c with a general (non-symmetric) G: strain sym(G), plus a small rotation.
  Eigen::Matrix3d G;
  G << 0.010, -0.004, 0.002, 0.006, -0.003, 0.005, -0.001, 0.007, 0.008;
  const Eigen::Vector3d c(0.1, -0.2, 0.05);
  Eigen::VectorXd x0 = energy.rest_state();
  for (Eigen::Index i = 0; i < mesh.X.rows(); ++i)
    if (fixed[i]) x0.segment<3>(3 * i) += G * mesh.X.row(i).transpose() + c;

  const StaticResult result = solve_static(energy, Eigen::VectorXd::Zero(x0.size()), fixed, x0);
  ASSERT_TRUE(result.converged);
  EXPECT_LE(result.iterations, 2);  // quadratic energy: one Newton step solves it

  const Eigen::Matrix3d strain = 0.5 * (G + G.transpose());
  double worst_strain = 0, worst_position = 0;
  for (int e = 0; e < energy.num_elements(); ++e) {
    const Eigen::Matrix3d F = energy.deformation_gradient(e, result.x);
    const Eigen::Matrix3d eps = 0.5 * (F + F.transpose()) - Eigen::Matrix3d::Identity();
    worst_strain = std::max(worst_strain, (eps - strain).cwiseAbs().maxCoeff());
  }
  for (Eigen::Index i = 0; i < mesh.X.rows(); ++i) {
    const Eigen::Vector3d expected = mesh.X.row(i).transpose() + G * mesh.X.row(i).transpose() + c;
    worst_position = std::max(worst_position, (result.x.segment<3>(3 * i) - expected).cwiseAbs().maxCoeff());
  }
  std::printf(
      "patch test: %d elements, %d Newton steps, |g| %.2e -> %.2e N, max strain error %.2e, "
      "max position error %.2e m\n",
      energy.num_elements(), result.iterations, result.initial_gradient_norm, result.gradient_norm,
      worst_strain, worst_position);
  EXPECT_LT(worst_strain, 1e-10);
  EXPECT_LT(worst_position, 1e-10);
}
