/// @file Contact physics against validation.md: the 26.565° incline (sticks at μ = 0.5, slides
/// at μ = 0.49 with a = g (sin θ − μ cos θ)), a box stack coming to rest, a landing box, and a
/// rocking prism coming to rest under its weight.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

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
  double landing_speed = 0;  // m/s: an upper bound of the speed at the first contact
  std::vector<Eigen::Vector2d> slide;  // (time since the first contact, distance down the slope), once in contact
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
  const int dof = sim.model().bodies[1].dof;
  const Eigen::Vector3d start = sim.q().segment<3>(dof);
  for (int k = 0; k < steps; ++k) {
    // The speed before the step that first touches, plus what gravity adds in that step.
    if (!t_contact) r.landing_speed = sim.qdot().segment<3>(dof).norm() + 9.81 * scene.time.dt;
    const StepStats s = sim.step();
    r.converged &= s.newton.converged;
    if (!t_contact && s.contacts > 0) t_contact = s.time;
    if (t_contact) r.slide.emplace_back(s.time - *t_contact, slope_travel(sim, start, down));
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

// The block lands (a Coulomb impact: friction takes μ times the normal impulse off its speed
// along the slope, as long as it slides faster than ε_v) and then slides with
// a = g (sin θ − μ cos θ). Fitting s(t) = s₀ + v₀ t + ½ a t² to its travel from 0.1 s after the
// first contact checks both.
TEST(Incline, SlidesAtMuPoint49WithTheAnalyticAcceleration) {
  const InclineRun r = run_incline(STIFFSOFT_SOURCE_DIR "/scenes/incline_slide.json", 0.0);
  EXPECT_TRUE(r.converged);
  const double theta = std::atan(0.5), g = 9.81, mu = 0.49;
  const double a = g * (std::sin(theta) - mu * std::cos(theta));
  std::vector<Eigen::Vector2d> fitted;
  for (const Eigen::Vector2d& p : r.slide)
    if (p.x() >= 0.1) fitted.push_back(p);
  ASSERT_GT(fitted.size(), 100u);
  Eigen::MatrixX3d basis(fitted.size(), 3);
  Eigen::VectorXd travel(fitted.size());
  for (std::size_t k = 0; k < fitted.size(); ++k) {
    const double t = fitted[k].x();
    basis.row(Eigen::Index(k)) << 1.0, t, 0.5 * t * t;
    travel(Eigen::Index(k)) = fitted[k].y();
  }
  const Eigen::Vector3d c = basis.colPivHouseholderQr().solve(travel);
  // A landing at speed v along the vertical leaves at most v_c = (sin θ − μ cos θ) v along the
  // slope. Friction is smoothed below the slip speed ε_v (less than μλ there), so where v_c < ε_v
  // the landing leaves the block at up to ε_v: a faster slide has full Coulomb friction and
  // so speed v_c. Here v_c = 1.75e-3 m/s is below ε_v, and the landing step's exact solution
  // (tolerance 1e-7 m/s, friction lagged to convergence) leaves 2.19e-3 m/s (docs/newton.md).
  const double coulomb = (std::sin(theta) - mu * std::cos(theta)) * r.landing_speed;
  const double v0_bound = std::max(coulomb, r.epsv);
  std::printf("μ = 0.49: a = %.5f m/s² (analytic %.5f, error %.2f %%), speed after landing %.2e m/s (Coulomb "
              "impact %.2e, ε_v %.2e), travel %.4f m\n",
              c(2), a, 100 * (c(2) / a - 1), c(1), coulomb, r.epsv, r.travel);
  EXPECT_NEAR(c(2), a, 0.01 * a);
  EXPECT_GE(c(1), -1e-4);
  EXPECT_LE(c(1), v0_bound);
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

// Friction lagged once, at each step's start, misses the contact that starts within the
// landing step: on the μ = tan θ incline the block then slides on at the speed it landed with.
// Lagged again at the result while the lag error exceeds ε_v / 10, the landing leaves it
// creeping no faster than ε_v, and only the landing's steps are solved again.
TEST(FrictionIterations, LaggingAgainMakesTheLandingStopTheBlock) {
  struct Landing {
    double speed = 0;  // m/s along the slope after 1 s
    double eps_v = 0;
    int relags = 0, steps_relagged = 0;
  };
  const auto land = [](int friction_iterations) {
    PreparedScene p = prepare_scene(STIFFSOFT_SOURCE_DIR "/scenes/incline_stick.json");
    p.settings.friction_iterations = friction_iterations;
    // Converged tightly, so that what is compared is the lag: with the default tolerance and
    // one lag, Newton's early stop in the stick zone happens to stop the block too.
    p.settings.tolerance = 1e-5;
    const double lag_tolerance = friction_resolution * p.settings.eps_v;
    Landing r;
    r.eps_v = p.settings.eps_v;
    Simulation sim(std::move(p.model), p.settings);
    for (int k = 0; k < 100; ++k) {
      const StepStats s = sim.step();
      EXPECT_TRUE(s.newton.converged);
      r.relags += s.friction_relags;
      r.steps_relagged += s.friction_relags > 0;
      // Short of the cap, a step ends only once the lag error is within ε_v / 10.
      if (s.friction_relags + 1 < friction_iterations) EXPECT_LE(s.friction_lag_error, lag_tolerance) << "step " << s.step;
    }
    r.speed = sim.qdot().segment<3>(sim.model().bodies[1].dof).norm();
    return r;
  };
  const Landing once = land(1), lagged = land(3);
  std::printf("speed after 1 s: lagged once %.2e m/s, up to 3 times %.2e m/s (eps_v %.2e; %d relags in %d steps)\n",
              once.speed, lagged.speed, lagged.eps_v, lagged.relags, lagged.steps_relagged);
  EXPECT_EQ(once.relags, 0);
  EXPECT_GT(once.speed, 10 * once.eps_v);
  EXPECT_GT(lagged.relags, 0);
  EXPECT_LE(lagged.steps_relagged, 10);
  EXPECT_LE(lagged.speed, lagged.eps_v);
}

/// A 0.1 m box 5 mm above a floor falling at 1 m/s, h = 0.01 s, d̂ = 1 mm, μ = 0.5; `solver`
/// holds the scene's solver keys.
std::string landing_box(const std::string& solver) {
  return R"({"description": "landing", "time": {"dt": 0.01}, "contact": {"dhat": 0.001, "mu": 0.5},
    "solver": {)" + solver + R"(},
    "bodies": [
      {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [1.0, 0.1, 1.0]}, "position": [0, -0.05, 0]},
      {"name": "box", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, 0.055, 0],
       "velocity": [0, -1, 0]}]})";
}

// With the default tolerance (1e-2 × diagonal / s: 0.14 mm per step against d̂ = 1 mm), the speed
// rule alone stops Newton in the steps after the landing with the box pressed to a few hundredths
// of d̂ from the floor (38 µm; 1.5 µm with solver.release_hessian 1), far from force balance: the log
// barrier pushes it out by about its gap per iteration, a step below the tolerance. Newton's gap
// rule (no active gap changing by more than 20 % in the last direction) keeps it where the
// barrier holds it.
TEST(Landing, NewtonDoesNotStopWithTheBoxPressedIntoTheBarrier) {
  const auto smallest_gap = [](const std::string& solver) {
    Simulation sim = stiffsoft::testing::simulate(landing_box(solver));
    double smallest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 10; ++k) {
      const StepStats s = sim.step();
      EXPECT_TRUE(s.newton.converged);
      smallest = std::min(smallest, s.smallest_distance);
    }
    return smallest;
  };
  const double with_rule = smallest_gap(""), speed_rule_only = smallest_gap(R"("gap_tolerance": 1e300)");
  std::printf("smallest gap over 10 steps: %.3e m with the gap rule, %.3e m with the speed rule alone (d-hat 1e-3 m)\n",
              with_rule, speed_rule_only);
  EXPECT_GT(with_rule, 0.5e-3);
  EXPECT_LT(speed_rule_only, 0.1 * with_rule);  // what the rule is for
}

// A hexagonal prism lying on a side face, rocked about its axis at the start as a cylinder of
// `full`'s resting pile rocked at t = 3 s, and three times faster (with full's ε_v, tolerance
// and κ), must come to rest with the floor carrying its weight. Newton used to take its
// converged direction's first trial whatever the energy did there; that step raised E, its
// error went into the next step, and the prism rocked for good, the floor's force alternating
// up to 11.6 N against a weight of 4.08 N. Started three times faster it also rocked, in a cycle
// of two steps, where a released contact (0.6 of its Hessian) on the loaded face overshot in a
// direction already within the tolerance (docs/newton.md, session 46).
TEST(Rest, APrismRockedOnAFaceComesToRestUnderItsWeight) {
  for (const double speed : {1.0, 3.0}) {
    const auto times = [speed](double v) { return std::to_string(speed * v); };
    Simulation sim = stiffsoft::testing::simulate(R"({"description": "rocking prism",
      "time": {"dt": 0.004166666666666667},
      "contact": {"dhat": 0.001, "mu": 0.3, "eps_v": 0.00318, "kappa": 14662461.08, "check_start_gaps": false},
      "solver": {"tolerance": 0.0318},
      "bodies": [
        {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [1.0, 0.05, 1.0]}, "position": [0, -0.025, 0]},
        {"name": "prism", "mesh": {"primitive": "cylinder", "radius": 0.04, "height": 0.1, "resolution": 6},
         "position": [0, 0.0356, 0], "rotation_deg": [90, 0, 0], "density": 1000.0,
         "velocity": [)" + times(0.0035) + ", " + times(-0.0038) + R"(, 0], "angular_velocity": [0, 0, )" +
                                                  times(-0.1325) + "]}]}");
    const BodyModel& prism = sim.model().bodies[1];
    const double weight = prism.mass * 9.81;
    double worst_force = 0, worst_speed = 0;
    for (int k = 0; k < 480; ++k) {
      const StepStats s = sim.step();
      ASSERT_TRUE(s.newton.converged) << "step " << s.step << ": " << s.newton.failure;
      if (k < 420) continue;  // the last quarter second
      const Eigen::Vector3d floor_force =
          sim.contact_forces().middleRows(prism.vertex_begin, prism.vertex_end - prism.vertex_begin).colwise().sum();
      worst_force = std::max(worst_force, std::abs(floor_force.y() - weight));
      worst_speed = std::max(worst_speed, sim.qdot().segment<3>(prism.dof).norm());
    }
    std::printf("%g x the cylinder's motion, last 0.25 s: floor force off the weight (%.3f N) by up to %.3e N, "
                "speed up to %.3e m/s\n", speed, weight, worst_force, worst_speed);
    EXPECT_LT(worst_force, 0.01 * weight) << speed << " x";
    EXPECT_LT(worst_speed, 1e-4) << speed << " x";
  }
}

// The lag error is a velocity: in the step where a box lands, friction was lagged where it had
// no contact, so the error is μ times the landing's normal impulse per mass, the change of the
// box's vertical velocity beyond gravity's (backward Euler). Newton's tolerance is tight here,
// so that the step's contact force is its impulse to within round-off.
TEST(FrictionIterations, TheLagErrorOfALandingIsMuTimesItsImpulsePerMass) {
  const double mu = 0.5, h = 0.01, g = 9.81;
  Simulation sim = stiffsoft::testing::simulate(landing_box(R"("tolerance": 0.001)"));
  const int dof = sim.model().bodies[1].dof;
  for (int k = 0; k < 10; ++k) {
    const double v_before = sim.qdot()(dof + 1);
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged);
    EXPECT_EQ(s.friction_relags, 0);  // the default lags once
    if (s.contacts == 0) continue;
    const double impulse_per_mass = sim.qdot()(dof + 1) - (v_before - g * h);
    std::printf("landing step %d: lag error %.4f m/s, mu x normal impulse / m = %.4f m/s\n", s.step,
                s.friction_lag_error, mu * impulse_per_mass);
    EXPECT_GT(impulse_per_mass, 0.5);
    EXPECT_NEAR(s.friction_lag_error, mu * impulse_per_mass, 0.02 * mu * impulse_per_mass);
    return;
  }
  FAIL() << "the box never landed";
}

// stats.csv's stick/slip columns: once landed, every friction stencil of the μ = 0.49 block
// slides and every one of the μ = 0.5 block sticks, with no change between Newton iterates;
// in the landing's steps some stencils change between the two within a step.
TEST(StickSlip, TheSlidingBlockSlidesAndTheStickingOneSticks) {
  for (const bool slides : {true, false}) {
    SceneSimulation run = make_simulation(std::string(STIFFSOFT_SOURCE_DIR "/scenes/") +
                                          (slides ? "incline_slide.json" : "incline_stick.json"));
    int landing_flips = 0;
    for (int k = 1; k <= 60; ++k) {
      const StepStats s = run.simulation.step();
      if (k <= 10) {
        landing_flips += s.stick_slip_flips;
        continue;
      }
      ASSERT_GT(s.contacts, 0) << "step " << k;
      EXPECT_EQ(slides ? s.sliding : s.sticking, s.contacts) << "step " << k;
      EXPECT_EQ(slides ? s.sticking : s.sliding, 0) << "step " << k;
      EXPECT_EQ(s.stick_slip_flips, 0) << "step " << k;
    }
    EXPECT_GT(landing_flips, 0) << (slides ? "slide" : "stick");
  }
}
