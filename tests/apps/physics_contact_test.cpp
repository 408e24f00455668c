/// @file Contact physics against validation.md: the 26.565° incline (sticks at μ = 0.5, slides
/// at μ = 0.49 with a = g (sin θ − μ cos θ)), and a box stack coming to rest.

#include <gtest/gtest.h>

#include <cmath>

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
  double duration;   // s
  bool converged;
};

InclineRun run_incline(const std::string& file) {
  SceneDescription scene = load_scene(file);
  Model model = build_model(scene, file);
  resolve_relative_defaults(scene, model);
  Simulation sim(std::move(model), simulation_settings(scene));
  const double theta = std::atan(0.5);
  // The slab's rotation about z by −θ makes "down the slope" (−cos θ, −sin θ, 0) or its mirror;
  // take the direction whose y is negative.
  const Eigen::Vector3d down(-std::cos(theta), -std::sin(theta), 0);
  const Eigen::Vector3d p0 = sim.q().segment<3>(sim.model().bodies[1].dof);
  InclineRun r{0, scene.contact.eps_v.value(), scene.time.duration, true};
  const int steps = int(std::lround(scene.time.duration / scene.time.dt));
  for (int k = 0; k < steps; ++k) r.converged &= sim.step().newton.converged;
  r.travel = std::abs(slope_travel(sim, p0, down));
  return r;
}

}  // namespace

TEST(Incline, SticksAtMuHalf) {
  const InclineRun r = run_incline(STIFFSOFT_SOURCE_DIR "/scenes/incline_stick.json");
  EXPECT_TRUE(r.converged);
  std::printf("μ = 0.5: travel %.3e m, creep bound ε_v t = %.3e m\n", r.travel, r.epsv * r.duration);
  EXPECT_LE(r.travel, r.epsv * r.duration);
}

TEST(Incline, SlidesAtMuPoint49WithTheAnalyticAcceleration) {
  const InclineRun r = run_incline(STIFFSOFT_SOURCE_DIR "/scenes/incline_slide.json");
  EXPECT_TRUE(r.converged);
  const double theta = std::atan(0.5), g = 9.81;
  const double a = g * (std::sin(theta) - 0.49 * std::cos(theta));
  const double expected = 0.5 * a * r.duration * r.duration;
  std::printf("μ = 0.49: travel %.4f m, analytic %.4f m (a = %.4f m/s²), error %.2f %%\n", r.travel, expected, a,
              100 * std::abs(r.travel - expected) / expected);
  EXPECT_NEAR(r.travel, expected, 0.02 * expected);
}
