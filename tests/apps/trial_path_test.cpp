/// @file TrialPath: the straight line q + α p, and the geodesic path that turns each affine
/// body along exp(α W) (I + α S) A; and what the geodesic line search buys a box that lands on a
/// corner with a stiff orthogonality potential.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <string>

#include <stiffsoft/coupling/solver/trial_path.hpp>
#include <stiffsoft/libabd/affine_body.hpp>
#include <stiffsoft/libabd/orthogonality_potential.hpp>

#include "scene_helpers.hpp"

using namespace stiffsoft;

namespace {

/// Two dynamic affine boxes and a fixed floor: DOF layout, motions, surfaces.
const Model& two_box_model() {
  static const PreparedScene p = prepare_scene(
      load_scene_from_string(R"({"description": "TrialPath test: two boxes over a floor.",
        "bodies": [{"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [2, 0.1, 2]}, "position": [0, -0.05, 0]},
                   {"name": "a", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [0, 0.5, 0]},
                   {"name": "b", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "position": [0.5, 0.5, 0]}]})",
                             STIFFSOFT_SOURCE_DIR, "trial_path.json", "trial_path"),
      "trial_path.json");
  return p.model;
}

/// q with body b's affine matrix replaced by A.
void set_affine(const Model& model, int b, const Eigen::Matrix3d& A, Eigen::VectorXd& q) {
  const int dof = model.bodies[b].dof;
  q.segment<12>(dof) = abd::make_q(q.segment<3>(dof), A);
}

/// A direction that turns every dynamic body by the angle-axis vector ω (rad) about its own
/// origin, without stretching it, and moves it by v (m): ΔA = [ω]× A.
Eigen::VectorXd turn(const Model& model, const Eigen::VectorXd& q, const Eigen::Vector3d& omega, const Eigen::Vector3d& v) {
  Eigen::VectorXd p = Eigen::VectorXd::Zero(q.size());
  for (const BodyModel& body : model.bodies) {
    if (body.dof < 0) continue;
    const Eigen::Matrix3d A = abd::affine_matrix(q.segment<12>(body.dof));
    Eigen::Matrix3d W;
    W << 0, -omega.z(), omega.y(), omega.z(), 0, -omega.x(), -omega.y(), omega.x(), 0;
    p.segment<12>(body.dof) = abd::make_q(v, W * A);
  }
  return p;
}

}  // namespace

TEST(TrialPath, IsTheStraightLineWhenOffOrWhenNoBodyTurns) {
  const Model& model = two_box_model();
  const Eigen::VectorXd q = model.initial_q();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  Eigen::VectorXd p(q.size());
  for (Eigen::Index i = 0; i < p.size(); ++i) p[i] = u(rng);
  Eigen::VectorXd out;
  const TrialPath off(model, q, p, false, 0);
  EXPECT_TRUE(off.straight());
  off.point(0.3, out);
  EXPECT_EQ(out, q + 0.3 * p);
  // A pure stretch (ΔA A⁻¹ symmetric) and translations: nothing turns.
  Eigen::VectorXd stretch = Eigen::VectorXd::Zero(q.size());
  for (const BodyModel& body : model.bodies)
    if (body.dof >= 0) stretch.segment<12>(body.dof) = abd::make_q(Eigen::Vector3d(0.1, 0, 0), 0.01 * Eigen::Matrix3d::Identity());
  const TrialPath no_turn(model, q, stretch, true, 0);
  EXPECT_TRUE(no_turn.straight());
  EXPECT_FALSE(TrialPath(model, q, p, true, 0).straight());
  // A turn whose straight-line stretch κ ν ‖W Wᵀ‖² is below the step's promised decrease.
  EXPECT_TRUE(TrialPath(model, q, p, true, 1e30).straight());
}

TEST(TrialPath, LeavesTheIterateAlongTheDirection) {
  // q′(0) = p, so gᵀp is the slope of E along either path: (q(ε) − q)/ε − p = O(ε).
  const Model& model = two_box_model();
  Eigen::VectorXd q = model.initial_q();
  set_affine(model, 1, Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix(), q);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  Eigen::VectorXd p(q.size());
  for (Eigen::Index i = 0; i < p.size(); ++i) p[i] = u(rng);
  const TrialPath path(model, q, p, true, 0);
  ASSERT_FALSE(path.straight());
  Eigen::VectorXd out;
  for (double eps : {1e-3, 1e-4, 1e-5}) {
    path.point(eps, out);
    const double error = ((out - q) / eps - p).norm() / p.norm();
    EXPECT_LT(error, 2 * eps) << "eps " << eps;  // first order in ε: the path's curvature, |W|² ≤ 0.5
    EXPECT_GT(error, 1e-3 * eps) << "eps " << eps;  // and not the straight line
  }
  path.point(0.0, out);
  EXPECT_EQ(out, q);
}

TEST(TrialPath, TurnsABodyWithoutStretchingIt) {
  // Along a pure turn ΔA = [ω]× A at a rotation A the geodesic trial is exp(α [ω]×) A exactly,
  // a rotation; the straight line stretches A by about α²|ω|² (‖AᵀA − I‖_F).
  const Model& model = two_box_model();
  Eigen::VectorXd q = model.initial_q();
  const Eigen::Matrix3d A0 = Eigen::AngleAxisd(1.1, Eigen::Vector3d(-1, 0.5, 2).normalized()).toRotationMatrix();
  set_affine(model, 1, A0, q);
  const Eigen::Vector3d omega(0.2, -0.3, 0.1), v(0.01, -0.02, 0.03);
  const Eigen::VectorXd p = turn(model, q, omega, v);
  const TrialPath path(model, q, p, true, 0);
  Eigen::VectorXd out;
  for (double alpha : {0.25, 0.5, 1.0}) {
    path.point(alpha, out);
    for (int b : {1, 2}) {
      const int dof = model.bodies[b].dof;
      const Eigen::Matrix3d A = abd::affine_matrix(q.segment<12>(dof));
      const Eigen::Matrix3d expected = Eigen::AngleAxisd(alpha * omega.norm(), omega.normalized()).toRotationMatrix() * A;
      EXPECT_LT((abd::affine_matrix(out.segment<12>(dof)) - expected).norm(), 1e-14) << "alpha " << alpha;
      EXPECT_LT(abd::orthogonality_error(out.segment<12>(dof)), 1e-14) << "alpha " << alpha;
      EXPECT_EQ(abd::translation(out.segment<12>(dof)), abd::translation(q.segment<12>(dof)) + alpha * v);
      const Eigen::VectorXd line = q + alpha * p;
      EXPECT_GT(abd::orthogonality_error(line.segment<12>(dof)), 0.5 * alpha * alpha * omega.squaredNorm());
    }
  }
}

TEST(TrialPath, PutsEachBlockAtItsOwnPoint) {
  // Per block, the point of the path at that block's α: body a turned at α = 0.3, body b at 0.8.
  const Model& model = two_box_model();
  Eigen::VectorXd q = model.initial_q();
  set_affine(model, 1, Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix(), q);
  const Eigen::VectorXd p = turn(model, q, Eigen::Vector3d(0.4, 0.1, -0.2), Eigen::Vector3d(0.02, -0.05, 0.01));
  const TrialPath path(model, q, p, true, 0);
  ASSERT_FALSE(path.straight());
  std::vector<double> alpha(model.blocks.size());
  alpha[std::size_t(model.bodies[1].block)] = 0.3;
  alpha[std::size_t(model.bodies[2].block)] = 0.8;
  Eigen::VectorXd mixed, at;
  path.point(model, alpha, mixed);
  for (int b : {1, 2}) {
    path.point(alpha[std::size_t(model.bodies[b].block)], at);
    EXPECT_EQ(mixed.segment<12>(model.bodies[b].dof), at.segment<12>(model.bodies[b].dof)) << "body " << b;
  }
}

TEST(TrialPath, WeighsTheStretchOfACutChord) {
  // Both boxes turn by 0.6 rad; CCD cut body a's island at β = 0.4 of the chord from q to q(α),
  // and left body b's whole. The stretch counts body a only: V⊥ at 0.4 of its chord, less V⊥ at
  // the path's own point q(0.4 α), a rotation.
  const Model& model = two_box_model();
  const Eigen::VectorXd q = model.initial_q();
  const Eigen::VectorXd p = turn(model, q, Eigen::Vector3d(0, 0.6, 0), Eigen::Vector3d(0.01, 0, 0));
  const TrialPath path(model, q, p, true, 0);
  BlockIslands islands(int(model.blocks.size()));
  islands.number();
  std::vector<double> bound(std::size_t(islands.count()), 1.0);
  const BodyModel& a = model.bodies[1];
  bound[std::size_t(islands.island(a.block))] = 0.4;
  const double alpha = 0.5;
  Eigen::VectorXd end, own;
  path.point(alpha, end);
  path.point(0.4 * alpha, own);
  const abd::Vector12d chord_point = q.segment<12>(a.dof) + 0.4 * (end - q).segment<12>(a.dof);
  const double expected = abd::orthogonality_potential(chord_point, a.kappa, a.volume) -
                          abd::orthogonality_potential(own.segment<12>(a.dof), a.kappa, a.volume);
  EXPECT_GT(expected, 0);
  EXPECT_NEAR(path.chord_stretch(islands, bound, alpha), expected, 1e-9 * expected);
  // Uncut (every β = 1), or on the straight line, nothing is counted.
  EXPECT_EQ(path.chord_stretch(islands, std::vector<double>(bound.size(), 1.0), alpha), 0);
  EXPECT_EQ(TrialPath(model, q, p, false, 0).chord_stretch(islands, bound, alpha), 0);
}

namespace {

/// A 0.1 m box turned onto a corner, dropped 0.3 m onto a floor, κ = 1e10 Pa, h = 1/240 s.
std::string corner_landing(bool geodesic) {
  return std::string(R"({"description": "corner landing",
    "time": {"dt": 0.004166667, "duration": 0.4},
    "contact": {"dhat": 0.001, "mu": 0.3},
    "solver": {"geodesic_line_search": )") + (geodesic ? "true" : "false") + R"(},
    "bodies": [{"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [0.61, 0.05, 0.61]}, "position": [0, -0.025, 0]},
               {"name": "box", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, 0.3, 0],
                "rotation_deg": [20, 35, 10], "density": 1000, "kappa": 1e10}]})";
}

}  // namespace

// Linear in A, Newton's step turns the landing box by stretching it, and κ = 1e10 answers the
// stretch with an energy its model does not see: the impact steps take 13–23 iterations. Along
// the rotation group they take 4–5 (docs/newton.md, "A geodesic line search"). Both runs stop
// at the same tolerance, so the box ends at rest in the same place.
TEST(GeodesicLineSearch, LandsABoxOnItsCornerInFewerIterations) {
  const auto run = [](bool geodesic, int& iterations, int& slowest) {
    Simulation sim = stiffsoft::testing::simulate(corner_landing(geodesic));
    iterations = slowest = 0;
    for (int k = 0; k < 96; ++k) {
      const StepStats s = sim.step();
      EXPECT_TRUE(s.newton.converged) << "step " << k + 1;
      EXPECT_GT(s.smallest_distance, 0);
      iterations += s.newton.iterations;
      slowest = std::max(slowest, s.newton.iterations);
    }
    return Eigen::VectorXd(sim.q());
  };
  int it_geodesic = 0, it_straight = 0, slowest_geodesic = 0, slowest_straight = 0;
  const Eigen::VectorXd q_geodesic = run(true, it_geodesic, slowest_geodesic);
  const Eigen::VectorXd q_straight = run(false, it_straight, slowest_straight);
  std::printf("Newton iterations over 96 steps: %d geodesic (slowest step %d), %d straight (slowest %d); "
              "final positions %.3e m apart\n",
              it_geodesic, slowest_geodesic, it_straight, slowest_straight,
              (q_geodesic.head<3>() - q_straight.head<3>()).norm());
  EXPECT_LT(slowest_geodesic, slowest_straight / 2);
  EXPECT_LT(it_geodesic, it_straight);
  EXPECT_LT((q_geodesic.head<3>() - q_straight.head<3>()).norm(), 1e-3);  // 1 % of the box
  EXPECT_LT((q_geodesic - q_straight).lpNorm<Eigen::Infinity>(), 1e-2);
}
