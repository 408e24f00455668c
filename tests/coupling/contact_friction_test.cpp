/// Lagged smoothed friction of one stencil: normal force and bases from the lagged state,
/// gradient and Hessian against finite differences below and above ε, PSD projection, the
/// majorizer Newton uses where a step would reverse a slide,
/// zero without friction, and the sliding force magnitude μλ.

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <stiffsoft/coupling/contact/friction.hpp>
#include "contact_stencils.hpp"
#include "finite_differences.hpp"

namespace stiffsoft::contact {
namespace {

using Eigen::Vector3d;
using testing::fd_gradient;
using testing::fd_jacobian;
using testing::min_eigenvalue;
using testing::relative_error;

constexpr PrimitivePair kAllPairs[] = {PrimitivePair::VertexVertex, PrimitivePair::EdgeVertex,
                                       PrimitivePair::EdgeEdge, PrimitivePair::FaceVertex};

using test_stencils::random_unit;
using test_stencils::stencil_at_distance;

/// Vertices of the first primitive (the vertex for VV/EV/FV, edge a for EE).
std::vector<int> first_primitive(PrimitivePair kind) {
  return kind == PrimitivePair::EdgeEdge ? std::vector<int>{0, 1} : std::vector<int>{0};
}

/// Random step whose tangential displacement has norm y (the normal part is random too).
Vector12d step_with_tangential_norm(const FrictionStencil& f, double y, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Vector12d dx;
  for (int i = 0; i < 12; ++i) dx[i] = n(rng);
  const Eigen::Matrix<double, 2, 12> T = tangent_operator(f);
  // Remove the tangential part, then add one of the requested size along a random direction.
  const Eigen::Matrix<double, 12, 2> Tp = T.transpose() * (T * T.transpose()).inverse();
  dx -= Tp * (T * dx);
  const Eigen::Vector2d u = Eigen::Vector2d(n(rng), n(rng)).normalized() * y;
  return 0.01 * dx + Tp * u;
}

TEST(FrictionStencil, NormalForceAndBasesComeFromTheLaggedState) {
  std::mt19937 rng(61);
  const double dhat = 0.1, kappa = 1e4;
  for (PrimitivePair kind : kAllPairs)
    for (int trial = 0; trial < 50; ++trial) {
      const double d = dhat * (0.1 + 0.8 * (trial % 5) / 4.0);
      const Vector12d x = stencil_at_distance(kind, d, rng);
      const FrictionStencil f = make_friction_stencil({kind}, x, dhat, kappa);
      EXPECT_EQ(f.kind, kind);
      // λ = κ |d b(d², d̂)/d d|, checked by differences in d.
      const double h = 1e-6 * d;
      const double dbdd = (barrier((d + h) * (d + h), dhat) - barrier((d - h) * (d - h), dhat)) / (2 * h);
      EXPECT_NEAR(f.normal_force, kappa * std::abs(dbdd), 1e-7 * f.normal_force);
      // Γ x = r joins the closest points (length d), P is orthonormal and tangent to it.
      const Vector3d r = f.Gamma * x;
      EXPECT_NEAR(r.norm(), d, 1e-12);
      EXPECT_LT((f.P.transpose() * f.P - Eigen::Matrix2d::Identity()).norm(), 1e-14);
      EXPECT_LT((f.P.transpose() * r).norm(), 1e-12);
      // Rigid translations of the stencil cause no relative displacement.
      Vector12d shift;
      shift << Vector3d(1, 2, 3), Vector3d(1, 2, 3), Vector3d(1, 2, 3), Vector3d(1, 2, 3);
      EXPECT_LT((f.Gamma * shift).norm(), 1e-12);
    }
  // Beyond d̂ there is no normal force.
  EXPECT_EQ(make_friction_stencil({PrimitivePair::VertexVertex}, stencil_at_distance(PrimitivePair::VertexVertex, 0.2, rng),
                                  dhat, kappa).normal_force, 0.0);
}

TEST(FrictionPotential, GradientAndHessianMatchFiniteDifferencesBelowAndAboveEpsilon) {
  const double dhat = 0.1, kappa = 1e4, mu = 0.4, eps = 1e-2;
  for (PrimitivePair kind : kAllPairs) {
    std::mt19937 rng(700 + int(kind));
    double worst_g = 0, worst_h = 0;
    for (int trial = 0; trial < 200; ++trial) {
      const FrictionStencil f =
          make_friction_stencil({kind}, stencil_at_distance(kind, 0.05, rng), dhat, kappa);
      // tangential slip from 0.02 ε (sticking) to 5 ε (sliding)
      const double y = eps * (trial % 2 == 0 ? 0.02 + 0.9 * (trial % 10) / 9.0 : 1.2 + 4.0 * (trial % 10) / 9.0);
      const Vector12d dx = step_with_tangential_norm(f, y, rng);
      const auto D = [&](const Eigen::VectorXd& z) { return friction_potential(f, Vector12d(z), mu, eps); };
      const auto G = [&](const Eigen::VectorXd& z) -> Eigen::VectorXd {
        return friction_potential_gradient(f, Vector12d(z), mu, eps);
      };
      const double h = 1e-4 * y;
      worst_g = std::max(worst_g, relative_error(friction_potential_gradient(f, dx, mu, eps), fd_gradient(D, dx, h)));
      worst_h = std::max(worst_h,
                         relative_error(friction_potential_hessian(f, dx, mu, eps, false), fd_jacobian(G, dx, h)));
    }
    std::printf("    friction kind %d: worst gradient error %.2e, Hessian error %.2e\n", int(kind), worst_g, worst_h);
    EXPECT_LT(worst_g, 1e-6) << "kind " << int(kind);
    EXPECT_LT(worst_h, 1e-5) << "kind " << int(kind);
  }
}

TEST(FrictionPotential, ProjectedHessianIsPsd) {
  const double dhat = 0.1, kappa = 1e4, mu = 0.5, eps = 1e-3;
  for (PrimitivePair kind : kAllPairs) {
    std::mt19937 rng(800 + int(kind));
    for (int trial = 0; trial < 100; ++trial) {
      const FrictionStencil f = make_friction_stencil({kind}, stencil_at_distance(kind, 0.03, rng), dhat, kappa);
      for (double y : {0.0, 0.3 * eps, 0.999 * eps, eps, 3 * eps}) {
        const Vector12d dx = step_with_tangential_norm(f, y, rng);
        const Matrix12d H = friction_potential_hessian(f, dx, mu, eps, false);
        const Matrix12d Hp = friction_potential_hessian(f, dx, mu, eps, true);
        EXPECT_GE(min_eigenvalue(Hp), -1e-10 * Hp.norm()) << int(kind) << " y " << y;
        // The exact 2×2 core is PSD for every y, so projecting changes (almost) nothing.
        EXPECT_LT((Hp - H).norm(), 1e-10 * H.norm()) << int(kind) << " y " << y;
        EXPECT_TRUE(Hp.allFinite());
      }
    }
  }
}

TEST(FrictionPotential, MajorizerIsPsdAboveTheExactHessianAndItsQuadraticAboveD) {
  const double dhat = 0.1, kappa = 1e4, mu = 0.5, eps = 1e-3;
  for (PrimitivePair kind : kAllPairs) {
    std::mt19937 rng(820 + int(kind));
    std::normal_distribution<double> normal;
    for (int trial = 0; trial < 50; ++trial) {
      const FrictionStencil f = make_friction_stencil({kind}, stencil_at_distance(kind, 0.03, rng), dhat, kappa);
      for (double y : {0.0, 0.3 * eps, 0.999 * eps, 3 * eps, 50 * eps}) {
        const Vector12d dx = step_with_tangential_norm(f, y, rng);
        const Matrix12d H = friction_potential_hessian(f, dx, mu, eps, false);
        const Matrix12d Hm = friction_majorizer_hessian(f, dx, mu, eps);
        ASSERT_TRUE(Hm.allFinite());
        EXPECT_GE(min_eigenvalue(Hm), -1e-10 * Hm.norm()) << int(kind) << " y " << y;
        EXPECT_GE(min_eigenvalue(Matrix12d(Hm - H)), -1e-10 * Hm.norm()) << int(kind) << " y " << y;
        // Its quadratic lies above D along every direction, near and far, including steps
        // that reverse the slide.
        const double D0 = friction_potential(f, dx, mu, eps);
        const Vector12d g = friction_potential_gradient(f, dx, mu, eps);
        for (int k = 0; k < 20; ++k) {
          Vector12d v;
          for (int i = 0; i < 12; ++i) v[i] = normal(rng);
          v *= std::pow(10.0, -1.0 + 0.2 * k) * std::max(y, eps) / v.norm();
          const double model = D0 + g.dot(v) + 0.5 * v.dot(Hm * v);
          EXPECT_LE(friction_potential(f, dx + v, mu, eps), model + 1e-12 * std::max(1.0, std::abs(model)))
              << int(kind) << " y " << y << " |v| " << v.norm();
        }
        if (y < 3 * eps) continue;
        // Sliding: reversing the slide (u → −u) is exactly where the exact Hessian's quadratic
        // falls below D (it has no curvature along û), and where the step test fires.
        const Vector12d back = -2 * dx;
        EXPECT_GT(friction_potential(f, dx + back, mu, eps), D0 + g.dot(back) + 0.5 * back.dot(H * back));
        EXPECT_TRUE(step_reverses_slide(f, dx, back, eps));
        EXPECT_FALSE(step_reverses_slide(f, dx, Vector12d(0.5 * dx), eps));   // slides on
        EXPECT_FALSE(step_reverses_slide(f, dx, Vector12d(-0.5 * dx), eps));  // slows, same side
      }
      // Sticking (‖u‖ < ε): the exact Hessian is stiff there already; the test never fires.
      const Vector12d stick = step_with_tangential_norm(f, 0.5 * eps, rng);
      EXPECT_FALSE(step_reverses_slide(f, stick, Vector12d(-4 * stick), eps));
    }
  }
}

TEST(FrictionPotential, IsZeroWithoutFrictionCoefficientOrNormalForce) {
  std::mt19937 rng(81);
  for (PrimitivePair kind : kAllPairs) {
    FrictionStencil f = make_friction_stencil({kind}, stencil_at_distance(kind, 0.05, rng), 0.1, 1e4);
    const Vector12d dx = step_with_tangential_norm(f, 0.1, rng);
    EXPECT_GT(friction_potential(f, dx, 0.5, 1e-3), 0.0);
    EXPECT_EQ(friction_potential(f, dx, 0.0, 1e-3), 0.0);
    EXPECT_TRUE(friction_potential_gradient(f, dx, 0.0, 1e-3).isZero(0.0));
    EXPECT_TRUE(friction_potential_hessian(f, dx, 0.0, 1e-3, true).isZero(0.0));
    f.normal_force = 0.0;
    EXPECT_EQ(friction_potential(f, dx, 0.5, 1e-3), 0.0);
    EXPECT_TRUE(friction_potential_gradient(f, dx, 0.5, 1e-3).isZero(0.0));
    EXPECT_TRUE(friction_potential_hessian(f, dx, 0.5, 1e-3, false).isZero(0.0));
  }
}

TEST(FrictionPotential, SlidingForceHasMagnitudeMuLambdaAndOpposesTheSlip) {
  std::mt19937 rng(82);
  const double mu = 0.3, eps = 1e-3;
  for (PrimitivePair kind : kAllPairs)
    for (int trial = 0; trial < 50; ++trial) {
      const FrictionStencil f = make_friction_stencil({kind}, stencil_at_distance(kind, 0.04, rng), 0.1, 1e4);
      const Vector12d dx = step_with_tangential_norm(f, 2 * eps + 0.1 * trial * eps, rng);
      const Vector12d g = friction_potential_gradient(f, dx, mu, eps);
      // Force on the first primitive (Σ of its vertices' forces) has magnitude μλ, and the
      // forces on the whole stencil balance (Σ_i c_i = 0).
      Vector3d on_first = Vector3d::Zero(), total = Vector3d::Zero();
      for (int i : first_primitive(kind)) on_first += g.segment<3>(3 * i);
      for (int i = 0; i < 4; ++i) total += g.segment<3>(3 * i);
      EXPECT_NEAR(on_first.norm(), mu * f.normal_force, 1e-12 * mu * f.normal_force);
      EXPECT_LT(total.norm(), 1e-12 * mu * f.normal_force);
      // −∇D is a dissipative force: it opposes the relative tangential slip.
      const Vector3d slip = f.P * (tangent_operator(f) * dx);
      EXPECT_NEAR(on_first.normalized().dot(slip.normalized()), 1.0, 1e-12);
      // Below ε the force is smaller than μλ (static regime of the smoothed model).
      const Vector12d dx_stick = step_with_tangential_norm(f, 0.5 * eps, rng);
      const Vector12d gs = friction_potential_gradient(f, dx_stick, mu, eps);
      Vector3d stick_first = Vector3d::Zero();
      for (int i : first_primitive(kind)) stick_first += gs.segment<3>(3 * i);
      EXPECT_NEAR(stick_first.norm(), mu * f.normal_force * friction_f1(0.5 * eps, eps), 1e-12 * mu * f.normal_force);
    }
}

TEST(FrictionPotential, SmoothingFunctionsAreConsistent) {
  const double eps = 2e-3;
  for (double y : {0.0, 1e-6, 1e-4, 1e-3, 1.999e-3, 2e-3, 5e-3}) {
    const double h = 1e-9;
    if (y > h) {
      EXPECT_NEAR(friction_f1(y, eps), (friction_f0(y + h, eps) - friction_f0(y - h, eps)) / (2 * h), 1e-6);
      EXPECT_NEAR(friction_f1_over_y(y, eps), friction_f1(y, eps) / y, 1e-9 / y);
    }
    EXPECT_GE(friction_f1(y, eps), 0.0);
    EXPECT_LE(friction_f1(y, eps), 1.0);
  }
  // C¹ of f₀ and continuity of f₁ at ε.
  EXPECT_NEAR(friction_f0(eps * (1 - 1e-6), eps), eps * (1 - 1e-6), 1e-18);  // f₀ − y = O((ε − y)³/ε²)
  EXPECT_NEAR(friction_f1(eps * (1 - 1e-12), eps), 1.0, 1e-11);
  EXPECT_DOUBLE_EQ(friction_f1_over_y(0.0, eps), 2.0 / eps);
}

TEST(FrictionStencil, DegenerateLaggedStatesGiveFiniteData) {
  const Vector3d o(0.2, 0.1, 0.0), ex(1, 0, 0), ey(0, 1, 0);
  // touching point pair (d = 0): no normal direction from r, any tangent plane is used
  const FrictionStencil vv = make_friction_stencil({PrimitivePair::VertexVertex}, pack_stencil(o, o, o, o), 0.1, 1e4);
  EXPECT_TRUE(vv.P.allFinite());
  EXPECT_EQ(vv.normal_force, std::numeric_limits<double>::infinity());  // documented: d = 0
  // vertex on the face: face normal is used
  const FrictionStencil fv =
      make_friction_stencil({PrimitivePair::FaceVertex}, pack_stencil(o + 0.1 * ex + 0.1 * ey, o, o + ex, o + ey), 0.1, 1e4);
  EXPECT_LT((fv.P.transpose() * Vector3d::UnitZ()).norm(), 1e-15);
  // mollified, exactly parallel, segment-distance edges
  const Stencil s{PrimitivePair::EdgeEdge, 1e-3, true};
  const FrictionStencil ee = make_friction_stencil(s, pack_stencil(o, o + ex, o + 0.05 * ey + 0.5 * ex, o + 0.05 * ey + 1.5 * ex), 0.1, 1e4);
  EXPECT_TRUE(ee.P.allFinite() && ee.Gamma.allFinite());
  EXPECT_EQ(ee.normal_force, 0.0);  // the mollifier vanishes for parallel edges
}

}  // namespace
}  // namespace stiffsoft::contact
