#include <stiffsoft/libfem/solve_static.hpp>

#include <gtest/gtest.h>

#include <stiffsoft/libfem/box_tet_mesh.hpp>
#include <stiffsoft/libfem/make_material.hpp>

using namespace stiffsoft::fem;

TEST(SolveStatic, ConvergesForALargeStretchOfANonlinearBlock) {
  // A 0.1 m cube of stable neo-Hookean (E = 1e5 Pa) clamped at z = 0 and pulled up at z = 0.1 m
  // by 500 N (nominal stress 5e4 Pa = E/2): far outside small strain, several Newton steps.
  for (const char* name : {"stable_neo_hookean", "fixed_corotated"}) {
    const TetMesh mesh = box_tet_mesh({0.1, 0.1, 0.1}, {3, 3, 3});
    const ElasticEnergy energy(mesh.X, mesh.T, make_material(name, 1e5, 0.4));
    const int N = energy.num_nodes();
    std::vector<bool> fixed(N);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * N);
    int top = 0;
    for (int i = 0; i < N; ++i) {
      fixed[i] = mesh.X(i, 2) < 1e-12;
      top += mesh.X(i, 2) > 0.1 - 1e-12;
    }
    for (int i = 0; i < N; ++i)
      if (mesh.X(i, 2) > 0.1 - 1e-12) f[3 * i + 2] = 500.0 / top;
    const StaticResult r = solve_static(energy, f, fixed, energy.rest_state());
    std::printf("%s: %d Newton steps, %d halvings, |g| %.3e -> %.3e N, top rises %.4f m\n", name,
                r.iterations, r.line_search_halvings, r.initial_gradient_norm, r.gradient_norm,
                r.x[3 * (N - 1) + 2] - 0.1);
    ASSERT_TRUE(r.converged) << name;
    EXPECT_GT(r.iterations, 2) << name;
    EXPECT_LE(r.iterations, 30) << name;
    EXPECT_LE(r.gradient_norm, StaticSettings{}.relative_tolerance * r.initial_gradient_norm) << name;
    EXPECT_FALSE(r.at_roundoff) << name;
    EXPECT_GT(r.x[3 * (N - 1) + 2] - 0.1, 0.02) << name;  // it stretched a lot
    for (const bool inverted : energy.inverted(r.x)) EXPECT_FALSE(inverted);
    for (int i = 0; i < N; ++i)
      if (fixed[i]) {
        EXPECT_EQ(r.x.segment<3>(3 * i), energy.rest_state().segment<3>(3 * i));
      }
  }
}

TEST(SolveStatic, RecoversRestShapeFromAnInvertedStart) {
  // "Squash and recover" in miniature: a stable neo-Hookean cube with its bottom clamped and all
  // other nodes mirrored below the clamp (every free element inverted) returns to rest.
  const TetMesh mesh = box_tet_mesh({0.1, 0.1, 0.1}, {2, 2, 2});
  const ElasticEnergy energy(mesh.X, mesh.T, make_material("stable_neo_hookean", 1e5, 0.3));
  const int N = energy.num_nodes();
  std::vector<bool> fixed(N);
  Eigen::VectorXd x0 = energy.rest_state();
  for (int i = 0; i < N; ++i) {
    fixed[i] = mesh.X(i, 2) < 1e-12;
    x0[3 * i + 2] *= -0.5;
  }
  int inverted = 0;
  for (const bool b : energy.inverted(x0)) inverted += b;
  EXPECT_EQ(inverted, energy.num_elements());
  const StaticResult r = solve_static(energy, Eigen::VectorXd::Zero(3 * N), fixed, x0);
  std::printf("recover: %d Newton steps, %d halvings, |g| %.3e -> %.3e N\n", r.iterations,
              r.line_search_halvings, r.initial_gradient_norm, r.gradient_norm);
  ASSERT_TRUE(r.converged);
  EXPECT_LT((r.x - energy.rest_state()).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(SolveStatic, StartingAtEquilibriumTakesNoStep) {
  const TetMesh mesh = box_tet_mesh({1, 1, 1}, {1, 1, 1});
  const ElasticEnergy energy(mesh.X, mesh.T, make_material("linear", 1e6, 0.3));
  std::vector<bool> fixed(energy.num_nodes(), false);
  fixed[0] = true;
  const StaticResult r =
      solve_static(energy, Eigen::VectorXd::Zero(3 * energy.num_nodes()), fixed, energy.rest_state());
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 0);
}

TEST(SolveStatic, FreeFloatingBodyIsASingularSystem) {
  const TetMesh mesh = box_tet_mesh({1, 1, 1}, {1, 1, 1});
  const ElasticEnergy energy(mesh.X, mesh.T, make_material("linear", 1e6, 0.3));
  const int N = energy.num_nodes();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * N);
  f[2] = 1;  // an unbalanced force on a body with no fixed node
  EXPECT_THROW(solve_static(energy, f, std::vector<bool>(N, false), energy.rest_state()), std::runtime_error);
  EXPECT_THROW(solve_static(energy, f, std::vector<bool>(N - 1, false), energy.rest_state()),
               std::invalid_argument);
}

TEST(SolveStatic, StopsAtTheRoundOffFloorOfTheGradient) {
  // A stiff bar (E = 1e9 Pa) bent by a small load: one Newton step solves the linear problem, and
  // ‖g‖ then sits at its round-off floor. With no gradient tolerance the decrement test stops it.
  const TetMesh mesh = box_tet_mesh({1, 0.1, 0.1}, {10, 1, 1});
  const ElasticEnergy energy(mesh.X, mesh.T, make_material("linear", 1e9, 0.3));
  const int N = energy.num_nodes();
  std::vector<bool> fixed(N);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * N);
  for (int i = 0; i < N; ++i) {
    fixed[i] = mesh.X(i, 0) < 1e-12;
    if (mesh.X(i, 0) > 1 - 1e-12) f[3 * i + 2] = -1;
  }
  StaticSettings settings;
  settings.relative_tolerance = 0;
  const StaticResult r = solve_static(energy, f, fixed, energy.rest_state(), settings);
  std::printf("round-off stop: %d Newton steps, |g| %.3e -> %.3e N\n", r.iterations, r.initial_gradient_norm,
              r.gradient_norm);
  EXPECT_TRUE(r.converged);
  EXPECT_TRUE(r.at_roundoff);
  EXPECT_LE(r.iterations, 2);
  EXPECT_LT(r.gradient_norm, 1e-6 * r.initial_gradient_norm);
}
