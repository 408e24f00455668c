// The rotation-variant SVD: F = U Σ Vᵀ with proper rotations, sorted σ, the reflection in σ₂,
// and singular values equal to Eigen's JacobiSVD, on random, inverted, repeated, rank-deficient
// and badly scaled matrices.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <stiffsoft/libfem/rotation_variant_svd.hpp>

using namespace stiffsoft::fem;

namespace {

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  return Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
}

/// Matrices a deformation gradient can be, and the hard ones for an SVD.
std::vector<Eigen::Matrix3d> hard_matrices() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Matrix3d> out;
  for (int k = 0; k < 2000; ++k) out.push_back(Eigen::Matrix3d::NullaryExpr([&] { return u(rng); }));
  for (const double strain : {1e-2, 1e-6, 1e-10, 1e-15}) {
    for (int k = 0; k < 50; ++k) {
      const Eigen::Matrix3d E = strain * Eigen::Matrix3d::NullaryExpr([&] { return u(rng); });
      out.push_back(random_rotation(rng) * (Eigen::Matrix3d::Identity() + E));
    }
  }
  const std::vector<Eigen::Vector3d> spectra{{1, 1, 1},   {2, 2, 1},     {2, 1, 1},     {1, 1, -1},
                                             {3, 1, 0},   {1, 0, 0},     {0, 0, 0},     {1, 1e-12, 1e-12},
                                             {1, 1, -1e-9}, {1e150, 1, 1e-150}, {1e-150, 1e-150, 1e-151}};
  for (const Eigen::Vector3d& s : spectra) {
    out.push_back(s.asDiagonal());
    for (int k = 0; k < 20; ++k) out.push_back(random_rotation(rng) * s.asDiagonal() * random_rotation(rng));
  }
  Eigen::Matrix3d twins = Eigen::Matrix3d::NullaryExpr([&] { return u(rng); });
  twins.col(2) = twins.col(0);  // rank 2
  out.push_back(twins);
  out.push_back(Eigen::Vector3d(1, 2, 3) * Eigen::RowVector3d(-1, 0.5, 2));  // rank 1
  return out;
}

}  // namespace

TEST(RotationVariantSvd, IsAnExactFactorisationWithRotationsAndSortedSignedValues) {
  for (const Eigen::Matrix3d& F : hard_matrices()) {
    const RotationVariantSvd svd = rotation_variant_svd(F);
    const double scale = F.norm();
    const std::string at = "F =\n" + [&] { std::ostringstream s; s << F; return s.str(); }();
    EXPECT_LT((svd.U.transpose() * svd.U - Eigen::Matrix3d::Identity()).norm(), 1e-14) << at;
    EXPECT_LT((svd.V.transpose() * svd.V - Eigen::Matrix3d::Identity()).norm(), 1e-14) << at;
    EXPECT_GT(svd.U.determinant(), 0) << at;
    EXPECT_GT(svd.V.determinant(), 0) << at;
    EXPECT_LE((svd.U * svd.sigma.asDiagonal() * svd.V.transpose() - F).norm(), 1e-14 * scale) << at;
    EXPECT_GE(svd.sigma(0), svd.sigma(1)) << at;
    EXPECT_GE(svd.sigma(1), std::abs(svd.sigma(2))) << at;
    // The sign of a singular F's determinant is round-off: checked where it is not.
    if (std::abs(F.determinant()) > 1e-10 * scale * scale * scale)
      EXPECT_EQ(svd.sigma(2) < 0, F.determinant() < 0) << at;
    const Eigen::Vector3d expected = Eigen::JacobiSVD<Eigen::Matrix3d>(F).singularValues();
    EXPECT_LE((svd.sigma.cwiseAbs() - expected).norm(), 1e-14 * scale) << at;
  }
}
