/// @file Contact physics against validation.md: the 26.565° incline (sticks at μ = 0.5, slides
/// at μ = 0.49 with a = g (sin θ − μ cos θ)), and a box stack coming to rest.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "scene_helpers.hpp"

using namespace stiffsoft;

namespace {

/// Distance the block has moved down the slope since the start (m).
double slope_travel(const Simulation& sim, const Eigen::Vector3d& p0, const Eigen::Vector3d& down) {
  const int dof = sim.model().bodies[1].dof;
  return (sim.q().segment<3>(dof) - p0).dot(down);
}

struct InclineRun {
  double travel;     // m, at the end
  double epsv;       // m/s
  double duration;   // s, in contact
  bool converged;
};

/// Runs an incline scene; travel counts from `settle` seconds after the block's first contact.
InclineRun run_incline(const std::string& file, double settle) {
  SceneSimulation run = make_simulation(file);
  const SceneDescription& scene = run.scene;
  Simulation& sim = run.simulation;
  const double theta = std::atan(0.5);
  // The slab's rotation about z by −θ makes "down the slope" (−cos θ, −sin θ, 0) or its mirror;
  // take the direction whose y is negative.
  const Eigen::Vector3d down(-std::cos(theta), -std::sin(theta), 0);
  // The block starts a few millimetres above the slab and lands with a little speed along the
  // slope; travel counts from `settle` seconds after its first contact.
  std::optional<Eigen::Vector3d> p0;
  std::optional<double> t_contact;
  double t0 = 0;
  InclineRun r{0, scene.contact.eps_v.value(), 0, true};
  const int steps = int(std::lround(scene.time.duration / scene.time.dt));
  for (int k = 0; k < steps; ++k) {
    const StepStats s = sim.step();
    r.converged &= s.newton.converged;
    if (!t_contact && s.contacts > 0) t_contact = s.time;
    if (!p0 && t_contact && s.time >= *t_contact + settle - 1e-9) {
      p0 = sim.q().segment<3>(sim.model().bodies[1].dof);
      t0 = s.time;
    }
  }
  EXPECT_TRUE(p0.has_value()) << "the block never touched the slab";
  r.duration = sim.time() - t0;
  r.travel = p0 ? std::abs(slope_travel(sim, *p0, down)) : 0.0;
  return r;
}

}  // namespace

// After the landing transient the block creeps no faster than ε_v (smoothed static friction).
TEST(Incline, SticksAtMuHalf) {
  const InclineRun r = run_incline(STIFFSOFT_SOURCE_DIR "/scenes/incline_stick.json", 0.5);
  EXPECT_TRUE(r.converged);
  std::printf("μ = 0.5: travel %.3e m, creep bound ε_v t = %.3e m\n", r.travel, r.epsv * r.duration);
  EXPECT_LE(r.travel, r.epsv * r.duration);
}

TEST(Incline, SlidesAtMuPoint49WithTheAnalyticAcceleration) {
  const InclineRun r = run_incline(STIFFSOFT_SOURCE_DIR "/scenes/incline_slide.json", 0.0);
  EXPECT_TRUE(r.converged);
  const double theta = std::atan(0.5), g = 9.81;
  const double a = g * (std::sin(theta) - 0.49 * std::cos(theta));
  const double expected = 0.5 * a * r.duration * r.duration;  // starts at rest on contact
  std::printf("μ = 0.49: travel %.4f m, analytic %.4f m (a = %.4f m/s²), error %.2f %%\n", r.travel, expected, a,
              100 * std::abs(r.travel - expected) / expected);
  EXPECT_NEAR(r.travel, expected, 0.02 * expected);
}

// validation.md: a stack of boxes comes to rest, upright, each box on the one below.
TEST(BoxStack, ComesToRestUprightAndStacked) {
  const std::string file = STIFFSOFT_SOURCE_DIR "/scenes/box_stack.json";
  SceneSimulation run = make_simulation(file);
  const SceneDescription& scene = run.scene;
  const double dhat = *scene.contact.dhat;
  Simulation& sim = run.simulation;
  const int steps = int(std::lround(scene.time.duration / scene.time.dt));
  StepStats last;
  int most_iterations_at_rest = 0;  // over the second half, when the stack has settled
  for (int k = 0; k < steps; ++k) {
    last = sim.step();
    ASSERT_TRUE(last.newton.converged) << "step " << last.step << ": " << last.newton.failure;
    if (2 * k >= steps) most_iterations_at_rest = std::max(most_iterations_at_rest, last.newton.iterations);
  }
  // Boxes in contact start Newton where they rest, not pressed into the barrier by q̃'s
  // free fall: a settled stack takes one iteration per step (two before that start).
  EXPECT_EQ(most_iterations_at_rest, 1);
  // At rest: the kinetic energy is a tiny fraction of the potential energy released by the fall.
  std::printf("after %.1f s: kinetic energy %.3e J, orthogonality error %.2e\n", sim.time(), last.kinetic_energy,
              last.orthogonality_error);
  EXPECT_LT(last.kinetic_energy, 1e-4);
  // Box k (0.2 m) rests on box k−1: centres 0.2 m apart plus a gap below d̂, and its centre stays
  // within 5 % of the box size of the axis (the triangulated faces are not symmetric, so the
  // contact forces are not either: a drift of a few millimetres is seen).
  double previous_y = 0.0, drift = 0.0;
  for (int b = 1; b < int(sim.model().bodies.size()); ++b) {
    const Eigen::Vector3d p = sim.q().segment<3>(sim.model().bodies[b].dof);
    const double expected_gap = b == 1 ? 0.1 : 0.2;  // the ground's top is at y = 0
    EXPECT_GT(p.y() - previous_y, expected_gap) << sim.model().bodies[b].name;
    EXPECT_LT(p.y() - previous_y, expected_gap + dhat) << sim.model().bodies[b].name;
    EXPECT_LT(std::hypot(p.x(), p.z()), 0.05 * 0.2) << sim.model().bodies[b].name;
    drift = std::max(drift, std::hypot(p.x(), p.z()));
    previous_y = p.y();
  }
  std::printf("largest horizontal drift of a box centre: %.2e m\n", drift);
}

// Convergence studies compare runs: the same scene must give the same trajectory, bit for bit,
// whatever the thread count and schedule.
TEST(Reproducibility, TwoRunsOfAPileAreIdentical) {
  const std::string file = STIFFSOFT_SOURCE_DIR "/scenes/light.json";
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    SceneSimulation run = make_simulation(file);
    Simulation& sim = run.simulation;
    for (int k = 0; k < 80; ++k) sim.step();  // past 60 steps: the piles are in contact
    return sim.q();
  };
  const Eigen::VectorXd a = run(1), b = run(2), c = run(2);
  EXPECT_EQ((a - b).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((b - c).cwiseAbs().maxCoeff(), 0.0);
}
