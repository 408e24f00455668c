#include <stiffsoft/libabd/mass_matrix.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

using namespace stiffsoft::abd;

TEST(MassMatrix, KineticEnergyMatchesPointMasses) {
  // A body of point masses: ½ Σ mₖ |ẋₖ|² must equal ½ q̇ᵀ M q̇ for any q̇.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::pair<double, Eigen::Vector3d>> points;
  MassProperties mp;
  for (int k = 0; k < 7; ++k) {
    const double m = 1 + u(rng) * 0.5;
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    points.emplace_back(m, x);
    mp.mass += m;
    mp.first += m * x;
    mp.second += m * x * x.transpose();
  }
  const Matrix12d M = mass_matrix(mp);
  for (int t = 0; t < 5; ++t) {
    Vector12d qdot;
    for (int i = 0; i < 12; ++i) qdot[i] = u(rng);
    double energy = 0;
    for (const auto& [m, x] : points) energy += 0.5 * m * (jacobian(x) * qdot).squaredNorm();
    EXPECT_NEAR(0.5 * qdot.dot(M * qdot), energy, 1e-12 * energy);
  }
}

TEST(MassMatrix, RigidVelocityGivesRigidKineticEnergy) {
  // Body-frame origin at the centre of mass: ½ q̇ᵀMq̇ = ½ m|v|² + ½ ωᵀ I ω for A = I.
  MassProperties mp{2.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.1, 0.2, 0.3).asDiagonal()};
  const Vector12d q = make_q(Eigen::Vector3d(1, 2, 3), Eigen::Matrix3d::Identity());
  const Eigen::Vector3d v(0.5, -1, 2), w(3, -2, 1);
  const Vector12d qdot = rigid_velocity(q, v, w);
  const double expected = 0.5 * mp.mass * v.squaredNorm() + 0.5 * w.dot(inertia_tensor(mp) * w);
  EXPECT_NEAR(0.5 * qdot.dot(mass_matrix(mp) * qdot), expected, 1e-12 * expected);
}

TEST(AffineBody, AngularVelocityInvertsRigidVelocity) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Vector12d q = make_q(Eigen::Vector3d(0.1, -2, 3), R);
  const Eigen::Vector3d w(0.3, -1.2, 2.5);
  EXPECT_LT((angular_velocity(q, rigid_velocity(q, Eigen::Vector3d(1, 0, 0), w)) - w).norm(), 1e-12);
}
