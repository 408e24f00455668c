#include <stiffsoft/libabd/orthogonality_potential.hpp>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <random>

#include "finite_differences.hpp"

using namespace stiffsoft;
using namespace stiffsoft::abd;
using stiffsoft::testing::fd_gradient;
using stiffsoft::testing::fd_jacobian;
using stiffsoft::testing::relative_error;

namespace {
/// A rotation perturbed by a random affine part of size `noise`, translated randomly.
Vector12d random_q(std::mt19937& rng, double noise) {
  std::uniform_real_distribution<double> u(-1, 1);
  const Eigen::Quaterniond r(u(rng), u(rng), u(rng), u(rng));
  Eigen::Matrix3d A = r.normalized().toRotationMatrix();
  for (int i = 0; i < 9; ++i) A(i / 3, i % 3) += noise * u(rng);
  return make_q(Eigen::Vector3d(u(rng), u(rng), u(rng)), A);
}
constexpr double kKappa = 1e5, kVolume = 0.3;
}  // namespace

TEST(OrthogonalityPotential, IsZeroForRotations) {
  std::mt19937 rng(1);
  for (int t = 0; t < 10; ++t) {
    const Vector12d q = random_q(rng, 0.0);
    EXPECT_NEAR(orthogonality_potential(q, kKappa, kVolume), 0.0, 1e-18 * kKappa);
    EXPECT_LT(orthogonality_potential_gradient(q, kKappa, kVolume).norm(), 1e-9 * kKappa);
  }
}

TEST(OrthogonalityPotential, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(2);
  for (int t = 0; t < 20; ++t) {
    const Vector12d q = random_q(rng, 0.3);
    const auto f = [](const Eigen::VectorXd& x) {
      return orthogonality_potential(x, kKappa, kVolume);
    };
    const Eigen::VectorXd g = orthogonality_potential_gradient(q, kKappa, kVolume);
    EXPECT_LT(relative_error(g, fd_gradient(f, q)), 1e-7);
  }
}

TEST(OrthogonalityPotential, HessianMatchesFiniteDifferencesOfGradient) {
  std::mt19937 rng(3);
  for (int t = 0; t < 20; ++t) {
    const Vector12d q = random_q(rng, 0.3);
    const auto g = [](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return orthogonality_potential_gradient(x, kKappa, kVolume);
    };
    const Eigen::MatrixXd H = orthogonality_potential_hessian(q, kKappa, kVolume, false);
    EXPECT_LT(relative_error(H, fd_jacobian(g, q)), 1e-7);
  }
}

TEST(OrthogonalityPotential, ProjectedHessianIsPositiveSemiDefinite) {
  std::mt19937 rng(4);
  bool saw_indefinite = false;
  for (int t = 0; t < 50; ++t) {
    // Compressed bodies (A shrunk) make the raw Hessian indefinite.
    Vector12d q = random_q(rng, 0.2);
    q.tail<9>() *= 0.5;
    const Eigen::MatrixXd H = orthogonality_potential_hessian(q, kKappa, kVolume, false);
    const Eigen::MatrixXd P = orthogonality_potential_hessian(q, kKappa, kVolume, true);
    const double scale = H.norm();
    saw_indefinite |= stiffsoft::testing::min_eigenvalue(H) < -1e-6 * scale;
    EXPECT_GE(stiffsoft::testing::min_eigenvalue(P), -1e-10 * scale);
  }
  EXPECT_TRUE(saw_indefinite) << "the test never exercised the projection";
}

TEST(OrthogonalityPotential, ProjectedHessianIsTheEigenClampOfTheHessian) {
  // The analytic eigensystem gives the same matrix as clamping a numerical eigen-decomposition
  // of the 9×9 A block: near rotations, compressed, stretched, reflected and degenerate A.
  std::mt19937 rng(5);
  std::vector<Vector12d> qs;
  for (int t = 0; t < 20; ++t) qs.push_back(random_q(rng, 0.3));
  for (int t = 0; t < 10; ++t) {
    Vector12d q = random_q(rng, 0.2);
    q.tail<9>() *= t < 5 ? 0.5 : 1.6;
    qs.push_back(q);
  }
  Vector12d reflected = random_q(rng, 0.05);
  reflected.segment<3>(3) *= -1;  // det A < 0
  qs.push_back(reflected);
  qs.push_back(make_q(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()));           // σ = 1, 1, 1
  qs.push_back(make_q(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 1, 0).asDiagonal()));  // flattened
  qs.push_back(make_q(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()));                // collapsed
  for (const Vector12d& q : qs) {
    const Matrix12d H = orthogonality_potential_hessian(q, kKappa, kVolume, false);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> es(H.bottomRightCorner<9, 9>());
    Matrix12d expected = Matrix12d::Zero();
    expected.bottomRightCorner<9, 9>() =
        es.eigenvectors() * es.eigenvalues().cwiseMax(0.0).asDiagonal() * es.eigenvectors().transpose();
    const Matrix12d P = orthogonality_potential_hessian(q, kKappa, kVolume, true);
    EXPECT_LT((P - expected).norm(), 1e-10 * std::max(H.norm(), kKappa * kVolume)) << "q = " << q.transpose();
  }
}
