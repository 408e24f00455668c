#include <stiffsoft/libfem/tet_element.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <string>

#include "finite_differences.hpp"
#include <stiffsoft/libfem/make_material.hpp>

using namespace stiffsoft::fem;
using stiffsoft::testing::fd_gradient;
using stiffsoft::testing::fd_jacobian;
using stiffsoft::testing::min_eigenvalue;
using stiffsoft::testing::relative_error;

namespace {

constexpr double kE = 1e6, kNu = 0.4;
const char* const kMaterials[] = {"linear", "fixed_corotated", "stable_neo_hookean"};

/// A random non-degenerate rest tet of size ≈ 0.1 m.
Vector12d random_rest_tet(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Vector12d X;
  X << 0, 0, 0, 0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1;
  for (int i = 0; i < 12; ++i) X[i] += 0.02 * u(rng);
  return X;
}

/// A deformation of X: random affine map plus a random per-node perturbation.
Vector12d deform(std::mt19937& rng, const Vector12d& X, double amount) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 9; ++i) A(i / 3, i % 3) += amount * u(rng);
  Vector12d x;
  for (int a = 0; a < 4; ++a)
    x.segment<3>(3 * a) = A * X.segment<3>(3 * a) + Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.01 * amount;
  return x;
}

/// Node 3 pushed through the face (0, 1, 2): an inverted element.
Vector12d invert(const Vector12d& X) {
  Vector12d x = X;
  const Eigen::Vector3d c = (X.segment<3>(0) + X.segment<3>(3) + X.segment<3>(6)) / 3;
  x.segment<3>(9) = c - 0.5 * (X.segment<3>(9) - c);
  return x;
}

}  // namespace

TEST(TetElement, RestVolumeAndIdentityDeformationGradient) {
  Vector12d X;
  X << 0, 0, 0, 2, 0, 0, 0, 3, 0, 0, 0, 4;
  const TetElement element = make_tet_element(X, 0);
  EXPECT_NEAR(element.volume, 2.0 * 3 * 4 / 6, 1e-15);
  EXPECT_LT((deformation_gradient(element, X) - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  // Reversed orientation: same volume, still F = I at rest.
  Vector12d Y = X;
  Y.segment<3>(3).swap(Y.segment<3>(6));
  EXPECT_NEAR(make_tet_element(Y, 0).volume, 4.0, 1e-15);
  EXPECT_LT((deformation_gradient(make_tet_element(Y, 0), Y) - Eigen::Matrix3d::Identity()).norm(), 1e-15);
}

TEST(TetElement, DeformationGradientOfAnAffineMapIsItsMatrix) {
  std::mt19937 rng(1);
  const Vector12d X = random_rest_tet(rng);
  const TetElement element = make_tet_element(X, 0);
  Eigen::Matrix3d A = Eigen::Matrix3d::Random();
  const Eigen::Vector3d c(0.3, -2, 5);
  Vector12d x;
  for (int a = 0; a < 4; ++a) x.segment<3>(3 * a) = A * X.segment<3>(3 * a) + c;
  EXPECT_LT((deformation_gradient(element, x) - A).norm(), 1e-13);
  // F is linear in x with ∂vec(F)/∂x the element's 9×12 Jacobian (translations drop out).
  EXPECT_LT((deformation_gradient_jacobian(element) * x - vec(A)).norm(), 1e-13);
}

TEST(TetElement, DegenerateRestTetNamesTheElement) {
  Vector12d X;
  X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5, 0.5, 1e-13;  // V ≈ 1.7e-14 ≤ 1e-12 ℓ³
  try {
    make_tet_element(X, 17);
    FAIL() << "degenerate tet accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("tetrahedron 17 is degenerate"), std::string::npos)
        << error.what();
  }
  X[11] = 1e-6;  // thin but valid: V ≈ 1.7e-7 ℓ³
  EXPECT_NO_THROW(make_tet_element(X, 17));
  // Coincident nodes.
  Vector12d Y = Vector12d::Zero();
  EXPECT_THROW(make_tet_element(Y, 3), std::invalid_argument);
}

TEST(TetElement, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(2);
  for (const char* name : kMaterials) {
    const auto material = make_material(name, kE, kNu);
    for (int t = 0; t < 10; ++t) {
      const Vector12d X = random_rest_tet(rng);
      const TetElement element = make_tet_element(X, t);
      const Vector12d x = t < 8 ? deform(rng, X, 0.3) : invert(X);
      const auto f = [&](const Eigen::VectorXd& y) { return tet_energy(element, *material, y); };
      // Step 1e-8 m on a 0.1 m tet: F changes by ~1e-7.
      EXPECT_LT(relative_error(tet_gradient(element, *material, x), fd_gradient(f, x, 1e-8)), 1e-6)
          << name << " sample " << t;
    }
  }
}

TEST(TetElement, HessianMatchesFiniteDifferencesOfGradient) {
  std::mt19937 rng(3);
  for (const char* name : kMaterials) {
    const auto material = make_material(name, kE, kNu);
    for (int t = 0; t < 10; ++t) {
      const Vector12d X = random_rest_tet(rng);
      const TetElement element = make_tet_element(X, t);
      const Vector12d x = t < 8 ? deform(rng, X, 0.3) : invert(X);
      const auto g = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd {
        return tet_gradient(element, *material, y);
      };
      const Matrix12d H = tet_hessian(element, *material, x, false);
      EXPECT_LT(relative_error(H, fd_jacobian(g, x, 1e-8)), 1e-6) << name << " sample " << t;
      EXPECT_LT(relative_error(H, H.transpose()), 1e-12);
    }
  }
}

TEST(TetElement, ProjectedHessianIsPositiveSemiDefinite) {
  std::mt19937 rng(4);
  for (const char* name : kMaterials) {
    const auto material = make_material(name, kE, kNu);
    for (int t = 0; t < 10; ++t) {
      const Vector12d X = random_rest_tet(rng);
      const TetElement element = make_tet_element(X, t);
      const Vector12d x = t < 5 ? deform(rng, X, 0.8) : invert(X);
      const Matrix12d H = tet_hessian(element, *material, x, true);
      EXPECT_GE(min_eigenvalue(H), -1e-10 * H.norm()) << name << " sample " << t;
      // Rigid translations stay in the kernel after projection.
      Vector12d translation;
      for (int a = 0; a < 4; ++a) translation.segment<3>(3 * a) = Eigen::Vector3d(1, 2, 3);
      EXPECT_LT((H * translation).norm(), 1e-10 * H.norm());
    }
  }
}

TEST(TetElement, NonlinearEnergyIsRotationInvariant) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const char* name : {"fixed_corotated", "stable_neo_hookean"}) {
    const auto material = make_material(name, kE, kNu);
    for (int t = 0; t < 10; ++t) {
      const Vector12d X = random_rest_tet(rng);
      const TetElement element = make_tet_element(X, t);
      const Vector12d x = t < 8 ? deform(rng, X, 0.3) : invert(X);
      const Eigen::Matrix3d Q =
          Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
      Vector12d y;
      for (int a = 0; a < 4; ++a) y.segment<3>(3 * a) = Q * x.segment<3>(3 * a) + Eigen::Vector3d(1, -1, 2);
      const double E = tet_energy(element, *material, x);
      EXPECT_NEAR(tet_energy(element, *material, y), E, 1e-10 * std::abs(E)) << name;
      // A rigid motion of the rest shape costs nothing.
      Vector12d r;
      for (int a = 0; a < 4; ++a) r.segment<3>(3 * a) = Q * X.segment<3>(3 * a);
      EXPECT_NEAR(tet_energy(element, *material, r), 0.0, 1e-12 * kE * element.volume) << name;
      EXPECT_LT(tet_gradient(element, *material, r).norm(), 1e-9 * kE * element.volume / 0.1) << name;
    }
  }
}
