// The shared conformance suite that every material runs (Drake's constitutive-model tests):
// P = ∂ψ/∂F and ∂P/∂F = ∂P/∂F against finite differences, projected ∂P/∂F PSD (also inverted and
// strongly compressed), zero stress at rest, linearisation equal to small-strain elasticity.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <string>

#include "finite_differences.hpp"
#include <stiffsoft/libfem/make_material.hpp>
#include <stiffsoft/libfem/project_psd.hpp>

using namespace stiffsoft::fem;
using stiffsoft::testing::fd_gradient;
using stiffsoft::testing::fd_jacobian;
using stiffsoft::testing::min_eigenvalue;
using stiffsoft::testing::relative_error;

namespace {

constexpr double kE = 1e6, kNu = 0.35;

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  return Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
}

/// R₁ diag(s) R₂ with random rotations: a deformation with prescribed signed singular values.
Eigen::Matrix3d with_singular_values(std::mt19937& rng, const Eigen::Vector3d& s) {
  return random_rotation(rng) * s.asDiagonal() * random_rotation(rng);
}

/// Test deformations: moderate, stretched, strongly compressed, and inverted (one negative σ).
std::vector<Eigen::Matrix3d> sample_deformations(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Matrix3d> Fs;
  for (int t = 0; t < 5; ++t) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
    for (int i = 0; i < 9; ++i) F(i / 3, i % 3) += 0.3 * u(rng);
    Fs.push_back(F);
  }
  Fs.push_back(with_singular_values(rng, {1.8, 1.3, 0.9}));
  Fs.push_back(with_singular_values(rng, {0.35, 0.2, 0.1}));  // strongly compressed, J = 0.007
  Fs.push_back(with_singular_values(rng, {1.2, 0.9, -0.4}));  // inverted
  Fs.push_back(with_singular_values(rng, {0.8, 0.5, -0.3}));  // inverted and compressed
  return Fs;
}

Vector9d vec_of(const Eigen::VectorXd& v) { return v; }

class MaterialSuite : public ::testing::TestWithParam<std::string> {
 protected:
  std::unique_ptr<Material> material = make_material(GetParam(), kE, kNu);
};

/// The models meant for large deformation (small-strain elasticity is not rotation invariant).
class NonlinearMaterialSuite : public MaterialSuite {};

}  // namespace

TEST_P(MaterialSuite, StressMatchesFiniteDifferencesOfEnergy) {
  std::mt19937 rng(1);
  for (const Eigen::Matrix3d& F : sample_deformations(rng)) {
    const auto psi = [&](const Eigen::VectorXd& f) { return material->psi(unvec(vec_of(f))); };
    const Eigen::VectorXd P = vec(material->P(F));
    EXPECT_LT(relative_error(P, fd_gradient(psi, vec(F))), 1e-7) << "F =\n" << F;
  }
}

TEST_P(MaterialSuite, StressDerivativeMatchesFiniteDifferencesOfStress) {
  std::mt19937 rng(2);
  for (const Eigen::Matrix3d& F : sample_deformations(rng)) {
    const auto P = [&](const Eigen::VectorXd& f) -> Eigen::VectorXd {
      return vec(material->P(unvec(vec_of(f))));
    };
    const Eigen::MatrixXd dPdF = material->dPdF(F);
    EXPECT_LT(relative_error(dPdF, fd_jacobian(P, vec(F))), 1e-7) << "F =\n" << F;
    EXPECT_LT(relative_error(dPdF, dPdF.transpose()), 1e-12);
  }
}

TEST_P(MaterialSuite, ProjectedStressDerivativeIsPositiveSemiDefinite) {
  std::mt19937 rng(3);
  std::vector<Eigen::Matrix3d> Fs = sample_deformations(rng);
  Fs.push_back(with_singular_values(rng, {0.05, 0.02, 0.01}));  // crushed
  Fs.push_back(with_singular_values(rng, {0.3, 0.2, -0.2}));    // inverted, σ₁ + σ₂ = 0 (R jumps)
  Fs.push_back(with_singular_values(rng, {1, 1, -1}));          // a reflection
  Fs.push_back(Eigen::Matrix3d::Zero());                        // collapsed to a point
  for (const Eigen::Matrix3d& F : Fs) {
    const Matrix9d H = material->dPdF(F);
    const Matrix9d Hp = material->dPdF_projected(F);
    ASSERT_TRUE(Hp.allFinite());
    const double scale = std::max(H.norm(), kE);
    EXPECT_GE(min_eigenvalue(Hp), -1e-10 * scale) << "F =\n" << F;
    // The projection only removes negative curvature: Hp − H = Q max(−Λ, 0) Qᵀ is PSD.
    EXPECT_GE(min_eigenvalue(Hp - H), -1e-10 * scale) << "F =\n" << F;
    EXPECT_TRUE(material->dPdF(F, true).isApprox(Hp));
  }
}

TEST_P(MaterialSuite, ProjectedStressDerivativeIsTheEigenClampOfTheStressDerivative) {
  // Whatever a model computes it by (an analytic eigensystem for stable neo-Hookean), the result
  // is the nearest PSD matrix: the numerical eigen-decomposition with negative eigenvalues
  // clamped to zero.
  std::mt19937 rng(6);
  std::vector<Eigen::Matrix3d> Fs = sample_deformations(rng);
  Fs.push_back(with_singular_values(rng, {1, 1, 1}));           // repeated singular values
  Fs.push_back(with_singular_values(rng, {0.9, 0.9, 0.5}));
  Fs.push_back(with_singular_values(rng, {0.3, 0.2, -0.2}));    // inverted, σ₁ + σ₂ = 0
  for (const Eigen::Matrix3d& F : Fs) {
    const Matrix9d expected = project_psd<9>(material->dPdF(F));
    EXPECT_LT((material->dPdF_projected(F) - expected).norm(), 1e-10 * std::max(expected.norm(), kE))
        << "F =\n" << F;
  }
}

TEST_P(MaterialSuite, IsStressFreeAtRest) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_NEAR(material->psi(I), 0.0, 1e-15 * kE);
  EXPECT_LT(material->P(I).norm(), 1e-15 * kE);
  EXPECT_NEAR(material->von_mises(I), 0.0, 1e-15 * kE);
}

TEST_P(NonlinearMaterialSuite, IsStressFreeUnderRotation) {
  std::mt19937 rng(4);
  for (int t = 0; t < 10; ++t) {
    const Eigen::Matrix3d R = random_rotation(rng);
    EXPECT_NEAR(material->psi(R), 0.0, 1e-9 * kE);
    EXPECT_LT(material->P(R).norm(), 1e-9 * kE);
  }
}

TEST_P(NonlinearMaterialSuite, IsRotationInvariant) {
  std::mt19937 rng(5);
  for (const Eigen::Matrix3d& F : sample_deformations(rng)) {
    const Eigen::Matrix3d Q = random_rotation(rng);
    EXPECT_NEAR(material->psi(Q * F), material->psi(F), 1e-12 * kE);
    EXPECT_LT(relative_error(material->P(Q * F), Q * material->P(F)), 1e-10);
  }
}

TEST_P(MaterialSuite, LinearisesToSmallStrainElasticity) {
  // Every model's tangent at F = I must be the linear-elastic one with the same E and ν, so
  // that E and ν mean the same thing whichever model a scene picks.
  const auto linear = make_material("linear", kE, kNu);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_LT(relative_error(material->dPdF(I), linear->dPdF(I)), 1e-12);
}

TEST_P(MaterialSuite, VonMisesOfUniaxialStressIsTheAxialStress) {
  // Uniaxial strain state of small-strain theory: ε = diag(e, −ν e, −ν e) gives σ = diag(E e, 0, 0).
  const double e = 1e-7;
  const Eigen::Matrix3d F = Eigen::Vector3d(1 + e, 1 - kNu * e, 1 - kNu * e).asDiagonal();
  EXPECT_NEAR(material->von_mises(F), kE * e, 1e-5 * kE * e);
}

TEST_P(MaterialSuite, VonMisesOfPureDilationIsZero) {
  for (const double s : {0.5, 1.2}) {
    const Eigen::Matrix3d F = s * Eigen::Matrix3d::Identity();
    EXPECT_LT(material->von_mises(F), 1e-12 * kE);
    EXPECT_GT(material->P(F).norm(), 1e-3 * kE);  // the stress itself is not zero
  }
}

TEST_P(MaterialSuite, RejectsPoissonRatioOfOneHalfAndAbove) {
  for (const double nu : {0.5, 0.6}) {
    try {
      make_material(GetParam(), kE, nu);
      ADD_FAILURE() << "nu = " << nu << " accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("nu = " + std::to_string(nu).substr(0, 3)), std::string::npos)
          << error.what();
      EXPECT_NE(std::string(error.what()).find("-1 < nu < 0.5"), std::string::npos) << error.what();
    }
  }
  EXPECT_THROW(make_material(GetParam(), kE, -1.0), std::invalid_argument);
  EXPECT_THROW(make_material(GetParam(), 0.0, kNu), std::invalid_argument);
  EXPECT_THROW(make_material(GetParam(), -1e6, kNu), std::invalid_argument);
  EXPECT_NO_THROW(make_material(GetParam(), kE, 0.499));
  EXPECT_NO_THROW(make_material(GetParam(), kE, -0.9));
}

INSTANTIATE_TEST_SUITE_P(AllMaterials, MaterialSuite,
                         ::testing::Values("linear", "fixed_corotated", "stable_neo_hookean"));
INSTANTIATE_TEST_SUITE_P(LargeDeformationMaterials, NonlinearMaterialSuite,
                         ::testing::Values("fixed_corotated", "stable_neo_hookean"));
