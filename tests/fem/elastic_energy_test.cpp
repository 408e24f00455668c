#include <stiffsoft/libfem/elastic_energy.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "finite_differences.hpp"
#include <stiffsoft/libfem/box_tet_mesh.hpp>
#include <stiffsoft/libfem/make_material.hpp>

using namespace stiffsoft::fem;
using stiffsoft::testing::fd_gradient;
using stiffsoft::testing::fd_jacobian;
using stiffsoft::testing::min_eigenvalue;
using stiffsoft::testing::relative_error;

namespace {

constexpr double kE = 1e5, kNu = 0.3;

ElasticEnergy small_block(const char* material) {
  TetMesh mesh = box_tet_mesh({0.2, 0.1, 0.1}, {2, 1, 1});  // 12 tets, 12 nodes
  return ElasticEnergy(mesh.X, mesh.T, make_material(material, kE, kNu));
}

Eigen::VectorXd perturbed(const ElasticEnergy& energy, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd x = energy.rest_state();
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += amount * u(rng);
  return x;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ElasticEnergy, IsZeroWithZeroGradientAtRest) {
  for (const char* name : {"linear", "fixed_corotated", "stable_neo_hookean"}) {
    const ElasticEnergy energy = small_block(name);
    const Eigen::VectorXd X = energy.rest_state();
    EXPECT_NEAR(energy.value(X), 0.0, 1e-15) << name;
    EXPECT_LT(energy.gradient(X).norm(), 1e-9) << name;
    EXPECT_LT(energy.von_mises(X).maxCoeff(), 1e-9) << name;
  }
}

TEST(ElasticEnergy, GlobalGradientAndHessianMatchFiniteDifferences) {
  for (const char* name : {"linear", "fixed_corotated", "stable_neo_hookean"}) {
    const ElasticEnergy energy = small_block(name);
    const Eigen::VectorXd x = perturbed(energy, 0.01, 7);
    const auto f = [&](const Eigen::VectorXd& y) { return energy.value(y); };
    const auto g = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd { return energy.gradient(y); };
    EXPECT_LT(relative_error(energy.gradient(x), fd_gradient(f, x, 1e-8)), 1e-6) << name;
    const Eigen::MatrixXd H = Eigen::MatrixXd(energy.hessian(x, false));
    EXPECT_LT(relative_error(H, fd_jacobian(g, x, 1e-8)), 1e-6) << name;
    EXPECT_LT(relative_error(H, H.transpose()), 1e-12) << name;
    const Eigen::MatrixXd Hp = Eigen::MatrixXd(energy.hessian(x, true));
    EXPECT_GE(min_eigenvalue(Hp), -1e-10 * Hp.norm()) << name;
  }
}

TEST(ElasticEnergy, AddGradientAccumulatesIntoASegment) {
  const ElasticEnergy energy = small_block("stable_neo_hookean");
  const Eigen::VectorXd x = perturbed(energy, 0.01, 8);
  const int n = 3 * energy.num_nodes();
  Eigen::VectorXd q = Eigen::VectorXd::Ones(n + 5);
  energy.add_gradient(x, q.segment(5, n));
  EXPECT_EQ(q.head(5), Eigen::VectorXd::Ones(5));
  EXPECT_LT((q.segment(5, n) - Eigen::VectorXd::Ones(n) - energy.gradient(x)).norm(), 1e-12);
}

TEST(ElasticEnergy, ElementHessiansScatterToTheGlobalHessian) {
  const ElasticEnergy energy = small_block("fixed_corotated");
  const Eigen::VectorXd x = perturbed(energy, 0.01, 9);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(x.size(), x.size());
  for (int e = 0; e < energy.num_elements(); ++e) {
    const ElementHessian h = energy.element_hessian(e, x, true);
    for (int a = 0; a < 4; ++a) {
      EXPECT_EQ(h.nodes[a], energy.tets()(e, a));
      for (int b = 0; b < 4; ++b)
        H.block<3, 3>(3 * h.nodes[a], 3 * h.nodes[b]) += h.H.block<3, 3>(3 * a, 3 * b);
    }
  }
  EXPECT_LT(relative_error(H, Eigen::MatrixXd(energy.hessian(x, true))), 1e-14);
  EXPECT_THROW(energy.element_hessian(energy.num_elements(), x, true), std::invalid_argument);
}

// The weighted form a coupled solver assembles: weight 1 is the plain element Hessian bit for
// bit, any other weight scales it (to round-off: the weight multiplies the volume first).
TEST(ElasticEnergy, WeightedElementHessiansAreTheScaledOnes) {
  const ElasticEnergy energy = small_block("stable_neo_hookean");
  const Eigen::VectorXd x = perturbed(energy, 0.01, 11);
  const double weight = 1.0 / (240.0 * 240.0);
  for (int e = 0; e < energy.num_elements(); ++e) {
    const ElementHessian plain = energy.element_hessian(e, x, true);
    ElementHessian once, weighted;
    energy.element_hessian(e, x, true, 1.0, once);
    EXPECT_EQ(once.H, plain.H) << "element " << e;
    EXPECT_EQ(once.nodes, plain.nodes) << "element " << e;
    energy.element_hessian(e, x, true, weight, weighted);
    EXPECT_LT(relative_error(Eigen::MatrixXd(weighted.H), Eigen::MatrixXd(weight * plain.H)), 1e-14) << "element " << e;
  }
  ElementHessian out;
  EXPECT_THROW(energy.element_hessian(-1, x, true, weight, out), std::invalid_argument);
}

TEST(ElasticEnergy, ValueIsTheOrderedSumOfElementValues) {
  TetMesh mesh = box_tet_mesh({1, 1, 1}, {6, 6, 6});  // 1296 tets: several TBB chunks
  const ElasticEnergy energy(mesh.X, mesh.T, make_material("stable_neo_hookean", kE, kNu));
  const Eigen::VectorXd x = perturbed(energy, 0.02, 10);
  const Eigen::VectorXd values = energy.element_values(x);
  double sum = 0;
  for (Eigen::Index e = 0; e < values.size(); ++e) sum += values[e];
  EXPECT_EQ(energy.value(x), sum);  // bitwise: the reduction order is fixed
  EXPECT_EQ(energy.gradient(x), energy.gradient(x));
}

TEST(ElasticEnergy, FlagsInvertedElements) {
  const ElasticEnergy energy = small_block("stable_neo_hookean");
  Eigen::VectorXd x = energy.rest_state();
  EXPECT_EQ(energy.inverted(x), std::vector<bool>(energy.num_elements(), false));
  // Mirror the whole block through the plane z = 0: every element inverts.
  for (int i = 0; i < energy.num_nodes(); ++i) x[3 * i + 2] *= -1;
  EXPECT_EQ(energy.inverted(x), std::vector<bool>(energy.num_elements(), true));
  EXPECT_GT(energy.value(x), 0.0);
  EXPECT_TRUE(energy.von_mises(x).allFinite());
}

TEST(ElasticEnergy, VonMisesOfUniformStretch) {
  // A uniaxial stretch e along x of a linear-elastic block with free lateral contraction
  // (x = X + diag(e, −ν e, −ν e) X): every element carries σ_xx = E e, so von Mises = E e.
  TetMesh mesh = box_tet_mesh({0.3, 0.1, 0.2}, {3, 1, 2});
  const ElasticEnergy energy(mesh.X, mesh.T, make_material("linear", kE, kNu));
  const double e = 1e-6;
  Eigen::VectorXd x = energy.rest_state();
  for (int i = 0; i < energy.num_nodes(); ++i) {
    x[3 * i] *= 1 + e;
    x[3 * i + 1] *= 1 - kNu * e;
    x[3 * i + 2] *= 1 - kNu * e;
  }
  const Eigen::VectorXd s = energy.von_mises(x);
  EXPECT_LT((s.array() - kE * e).abs().maxCoeff(), 1e-5 * kE * e);
}

TEST(ElasticEnergy, RejectsBadMeshesNamingTheElement) {
  TetMesh mesh = box_tet_mesh({1, 1, 1}, {1, 1, 1});
  Eigen::MatrixX4i T = mesh.T;
  T(4, 2) = 8;
  EXPECT_EQ(message_of([&] { ElasticEnergy(mesh.X, T, make_material("linear", kE, kNu)); }),
            "libfem: tetrahedron 4 has node index 8; expected 0 <= index < 8");
  T = mesh.T;
  T(2, 3) = T(2, 0);
  EXPECT_EQ(message_of([&] { ElasticEnergy(mesh.X, T, make_material("linear", kE, kNu)); }),
            "libfem: tetrahedron 2 repeats node " + std::to_string(T(2, 0)));
  Eigen::MatrixX3d X = mesh.X;
  X.row(mesh.T(5, 3)) = X.row(mesh.T(5, 0));  // tet 5 (and neighbours) collapse
  EXPECT_NE(
      message_of([&] { ElasticEnergy(X, mesh.T, make_material("linear", kE, kNu)); }).find("is degenerate"),
      std::string::npos);
  EXPECT_NE(message_of([&] { ElasticEnergy(mesh.X, mesh.T, nullptr); }), "");
  const ElasticEnergy energy(mesh.X, mesh.T, make_material("linear", kE, kNu));
  EXPECT_THROW(energy.value(Eigen::VectorXd::Zero(5)), std::invalid_argument);
}
