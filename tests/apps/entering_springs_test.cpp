/// @file Springs on the pairs CCD finds entering d̂ (EnteringSprings, BarrierTerm::entering_pairs):
/// which pairs the barrier reports, what the springs' direction satisfies, and what they buy a
/// box that lands fast on another.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/SparseCholesky>

#include <stiffsoft/coupling/contact/constraint_set.hpp>
#include <stiffsoft/coupling/contact/distance_classification.hpp>
#include <stiffsoft/coupling/solver/entering_springs.hpp>
#include <stiffsoft/coupling/terms/barrier_term.hpp>

#include "scene_helpers.hpp"

using namespace stiffsoft;

namespace {

/// A box resting on a fixed floor, a second box falling flat onto it at 3 m/s (about 12 mm per
/// step, twelve times d̂) and a third falling onto the floor; with friction. `turned`: the
/// falling boxes turned onto an edge and a corner.
std::string landing(bool springs, bool turned) {
  return std::string(R"({"description": "a fast landing",
    "time": {"dt": 0.004166667},
    "contact": {"dhat": 0.001, "mu": 0.3},
    "solver": {"entering_springs": )") + (springs ? "true" : "false") + R"(},
    "bodies": [
      {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [2, 0.1, 2]}, "position": [0, -0.05, 0]},
      {"name": "low", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, 0.052, 0]},
      {"name": "high", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0.01, 0.2, 0],
       "rotation_deg": )" + (turned ? "[20, 35, 10]" : "[0, 0, 0]") + R"(, "velocity": [0, -6, 0]},
      {"name": "beside", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0.4, 0.15, 0.1],
       "rotation_deg": )" + (turned ? "[40, 0, 15]" : "[0, 0, 0]") + R"(, "velocity": [0.2, -3, 0]}]})";
}

/// The distance of an entering pair's stencil at x.
double stencil_distance(const Eigen::MatrixX3d& x, const EnteringPair& e) {
  const auto row = [&](int i) -> Eigen::Vector3d { return x.row(e.vertices[std::size_t(i)]).transpose(); };
  return std::sqrt(e.vertex_face ? contact::point_triangle_squared_distance(row(0), row(1), row(2), row(3))
                                 : contact::segment_segment_squared_distance(row(0), row(1), row(2), row(3)));
}

}  // namespace

// At every direction whose move CCD cuts, the barrier reports pairs farther than d̂ with their
// slack down to 0.8 d̂ and the gradient of their distance; the springs' direction descends, holds
// each acting pair's linearised gap near its target where the plain direction ran through it,
// and leaves Newton's matrix as it found it.
TEST(EnteringSprings, StopEachEnteringPairNearItsTargetGapAndDescend) {
  Simulation sim = stiffsoft::testing::simulate(landing(false, true));
  const double dhat = 0.001;
  int directions = 0, pairs_seen = 0, crossed = 0;
  double worst_gradient = 0, worst_gap = 0, worst_restore = 0;
  sim.observe_newton([&](const NewtonIterate& it) {
    const Eigen::MatrixX3d dx = it.model.surface_step(it.p);
    BlockIslands islands(int(it.model.blocks.size()));
    for (const EnergyTerm* t : it.terms) t->join_coupled_blocks(it.c, dx, islands);
    islands.number();
    std::vector<double> bound(std::size_t(islands.count()), 1.0);
    for (const EnergyTerm* t : it.terms) t->max_step_per_island(it.c, it.p, dx, islands, bound);
    std::vector<EnteringPair> pairs;
    for (const EnergyTerm* t : it.terms) t->entering_pairs(it.c, pairs);
    if (pairs.empty()) return;
    ++directions;
    for (const EnteringPair& e : pairs) {
      ++pairs_seen;
      const double d = stencil_distance(it.c.x, e);
      EXPECT_GE(d, dhat);
      EXPECT_NEAR(e.slack, d - BarrierTerm::kEnteringGap * dhat, 1e-12);
      // ∇d by central differences along a random move of the four points.
      const contact::Vector12d delta = contact::Vector12d::Random();
      const double eps = 1e-8;
      Eigen::MatrixX3d plus = it.c.x, minus = it.c.x;
      for (int i = 0; i < 4; ++i) {
        plus.row(e.vertices[std::size_t(i)]) += eps * delta.segment<3>(3 * i).transpose();
        minus.row(e.vertices[std::size_t(i)]) -= eps * delta.segment<3>(3 * i).transpose();
      }
      const double slope = (stencil_distance(plus, e) - stencil_distance(minus, e)) / (2 * eps);
      worst_gradient = std::max(worst_gradient, std::abs(slope - e.normal.dot(delta)) / delta.norm());
      crossed += e.normal.dot(gather(dx, e.vertices)) + e.slack < 0;
    }
    BlockHessian H = it.H;
    const Eigen::VectorXd probe = Eigen::VectorXd::Random(it.p.size());
    const Eigen::VectorXd H_probe = H.multiply(probe);
    const EnteringSprings::Solve solve = [&](const Eigen::VectorXd& g, Eigen::VectorXd& p) {
      const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper> ldlt(H.upper());
      if (ldlt.info() != Eigen::Success) return false;
      p = ldlt.solve(-g);
      return true;
    };
    EnteringSprings springs(it.model, pairs);
    ASSERT_EQ(springs.size(), pairs.size());
    Eigen::VectorXd p = it.p;
    if (!springs.solve(H, it.g, solve, p)) return;  // kept the direction: not a descent one
    EXPECT_LT(it.g.dot(p), 0.0);
    worst_restore = std::max(worst_restore, (H.multiply(probe) - H_probe).norm() / H_probe.norm());
    // A spring acting at the end lets its pair's linearised gap below the target by no more
    // than the force it takes over the spring's stiffness: a small fraction of the slack.
    const Eigen::MatrixX3d dx_springs = it.model.surface_step(p);
    for (const EnteringPair& e : pairs)
      worst_gap = std::max(worst_gap, -(e.normal.dot(gather(dx_springs, e.vertices)) + e.slack) / e.slack);
  });
  int contact_steps = 0;
  for (int k = 0; k < 30; ++k) contact_steps += sim.step().contacts > 0;
  std::printf("%d cut directions with %d entering pairs (%d run through by the plain direction); worst ∇d error "
              "%.2e, worst gap below the target %.3f of the slack, H restored to %.1e\n",
              directions, pairs_seen, crossed, worst_gradient, worst_gap, worst_restore);
  EXPECT_GE(contact_steps, 10);
  EXPECT_GE(directions, 3);
  EXPECT_GT(crossed, 0);
  EXPECT_LT(worst_gradient, 1e-6);
  EXPECT_LT(worst_gap, 0.5);
  EXPECT_LT(worst_restore, 1e-10);
}

// The fast landings with and without the springs: every step converges free of intersections,
// the springs take fewer CCD-limited iterations and no more in all, and the boxes come to rest at
// the same heights.
TEST(EnteringSprings, AFastLandingTakesFewerCutDirections) {
  const auto run = [](bool springs, int& iterations, int& cut, int& sprung, Eigen::VectorXd& q) {
    Simulation sim = stiffsoft::testing::simulate(landing(springs, false));
    iterations = cut = sprung = 0;
    for (int k = 0; k < 60; ++k) {
      const StepStats s = sim.step();
      EXPECT_TRUE(s.newton.converged) << "step " << k + 1;
      EXPECT_GT(s.smallest_distance, 0);
      iterations += s.newton.iterations;
      cut += s.newton.ccd_limited_iterations;
      sprung += s.newton.entering_directions;
    }
    Eigen::Vector3d heights;  // each box's centre height, m
    for (int b = 1; b <= 3; ++b) heights[b - 1] = sim.q()[sim.model().bodies[std::size_t(b)].dof + 1];
    q = sim.q();
    return heights;
  };
  int it_on = 0, it_off = 0, cut_on = 0, cut_off = 0, sprung_on = 0, sprung_off = 0;
  Eigen::VectorXd q_on, q_off;
  const Eigen::Vector3d y_on = run(true, it_on, cut_on, sprung_on, q_on);
  const Eigen::Vector3d y_off = run(false, it_off, cut_off, sprung_off, q_off);
  std::printf("60 steps: %d Newton iterations (%d CCD-limited, %d with springs) with the springs, %d (%d) without; "
              "largest difference of the boxes' heights %.2e m, of any DOF %.2e\n",
              it_on, cut_on, sprung_on, it_off, cut_off, (y_on - y_off).lpNorm<Eigen::Infinity>(),
              (q_on - q_off).lpNorm<Eigen::Infinity>());
  EXPECT_EQ(sprung_off, 0);
  EXPECT_GT(sprung_on, 0);
  EXPECT_LT(cut_on, cut_off);
  EXPECT_LE(it_on, it_off);
  // Both rest on the same boxes: the heights agree to a tenth of d̂ (the barrier's equilibrium
  // gap under the same weight); where they slid to differs by what Newton's tolerance leaves
  // of the landing (ε_d h, 0.1 mm per step here), which friction then keeps.
  EXPECT_LT((y_on - y_off).lpNorm<Eigen::Infinity>(), 1e-4);
}
