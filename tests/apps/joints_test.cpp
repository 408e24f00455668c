/// @file Joints on small inline scenes: pendulum period and damping against validation.md,
/// equalities held at every step, limits never crossed, damping monotone in k_d.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <stiffsoft/libabd/affine_body.hpp>
#include <stiffsoft/libabd/orthogonality_potential.hpp>
#include <stiffsoft/coupling/joints/joint_measures.hpp>
#include <stiffsoft/io/joint_frame_reader.hpp>
#include "scene_helpers.hpp"

using namespace stiffsoft;
using stiffsoft::testing::simulate;

namespace {

constexpr double kG = 9.81;

/// A number for an inline JSON scene, all digits kept (std::to_string keeps six decimals).
std::string num(double x) {
  std::ostringstream out;
  out << std::setprecision(17) << x;
  return out.str();
}

/// A cube bob (side a = 0.1 m, 1 kg) whose centre hangs L below a world pivot at the origin,
/// started at angle θ₀ from the vertical in the xy plane, joined by `kind` (ball or hinge
/// about z). No contact: nothing else in the scene.
std::string pendulum(const std::string& kind, const std::string& integrator, double dt, double duration,
                     double length, double theta0, const std::string& joint_extra = "") {
  const double x = length * std::sin(theta0), y = -length * std::cos(theta0);
  return R"({"description": "pendulum", "time": {"dt": )" + num(dt) + R"(, "duration": )" + num(duration) +
         R"(, "integrator": ")" + integrator + R"("},
    "solver": {"tolerance": 1e-8},
    "bodies": [{"name": "bob", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "density": 1000,
                "position": [)" + std::to_string(x) + ", " + std::to_string(y) + R"(, 0],
                "rotation_deg": [0, 0, )" + std::to_string(theta0 * 180 / M_PI) + R"(]}],
    "joints": [{"name": "pivot", "kind": ")" + kind + R"(", "body_a": "bob", "anchor": [0, 0, 0])" +
         (kind == "hinge" ? R"(, "axis": [0, 0, 1])" : "") + joint_extra + "}]}";
}

/// Angle of the bob's centre from the downward vertical (rad).
double angle(const Simulation& sim) {
  const Eigen::Vector3d p = sim.q().head<3>();
  return std::atan2(p.x(), -p.y());
}

/// ω² = m g L / I_pivot of the cube pendulum (I_pivot = m a²/6 + m L²).
double omega(double length) { return std::sqrt(kG * length / (0.01 / 6 + length * length)); }

/// Linear interpolation of the time where θ crosses zero between two steps.
double crossing(double t0, double a0, double t1, double a1) { return t0 + (t1 - t0) * a0 / (a0 - a1); }

}  // namespace

TEST(Pendulum, Bdf2PeriodMatchesThePhysicalPendulum) {
  // validation.md: T = 2π √(I_pivot / (m g L)) (1 + θ₀²/16 + 11 θ₀⁴/3072).
  const double L = 1.0, theta0 = 0.1, h = 1e-3;
  Simulation sim = simulate(pendulum("ball", "bdf2", h, 3, L, theta0));
  const double T = 2 * M_PI / omega(L) * (1 + theta0 * theta0 / 16 + 11 * std::pow(theta0, 4) / 3072);
  std::vector<double> crossings;
  double previous = angle(sim), t_previous = 0;
  while (crossings.size() < 3 && sim.time() < 2 * T) {
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged) << s.newton.failure;
    ASSERT_LT(s.joint_error, 1e-9) << "step " << s.step;
    const double a = angle(sim);
    if ((previous > 0) != (a > 0)) crossings.push_back(crossing(t_previous, previous, sim.time(), a));
    previous = a;
    t_previous = sim.time();
  }
  ASSERT_EQ(crossings.size(), 3u);
  const double measured = crossings[2] - crossings[0];
  std::printf("pendulum L = 1 m, θ₀ = 0.1, BDF-2 h = 1e-3: T = %.6f s, analytic %.6f s (%.3f %%)\n", measured, T,
              100 * (measured / T - 1));
  EXPECT_NEAR(measured / T, 1.0, 5e-3);
}

TEST(Pendulum, ConvergesWhereTheToleranceMeetsRoundOff) {
  // With the test's ε_d = 1e-8 m/s, a step's last directions move the bob by about 1e-11 m and
  // lower E by less than rounding the DOFs changes it (the joint holds the bob against a
  // gradient across the directions it cannot move). Before the line search allowed for that
  // noise, some of these starts stalled at 200 iterations (docs/newton.md, session 40).
  for (const double theta0 : {0.0998, 0.0999, 0.1, 0.1001, 0.1002, 0.1003}) {
    Simulation sim = simulate(pendulum("ball", "bdf2", 1e-3, 0.02, 1.0, theta0));
    for (int k = 0; k < 20; ++k) {
      const StepStats s = sim.step();
      ASSERT_TRUE(s.newton.converged) << "θ₀ = " << theta0 << ", step " << s.step << ": " << s.newton.failure;
    }
  }
}

TEST(Pendulum, BackwardEulerDampsAsPredictedAndBdf2KeepsTheAmplitude) {
  // validation.md: BE multiplies the amplitude by 1/√(1 + z²) per step (z = ω h): 61 % after
  // 10 s for L = 1 m, h = 0.01; BDF-2 keeps ≈ 99.98 %.
  const double L = 1.0, theta0 = 0.1, h = 0.01, duration = 10;
  const double z = omega(L) * h;
  for (const std::string integrator : {"backward_euler", "bdf2"}) {
    Simulation sim = simulate(pendulum("hinge", integrator, h, duration, L, theta0));
    double peak = 0, t_peak = 0, a_prev2 = 0, a_prev = angle(sim);
    while (sim.time() < duration - 1e-9) {
      const StepStats s = sim.step();
      ASSERT_TRUE(s.newton.converged) << s.newton.failure;
      ASSERT_LT(s.joint_error, 1e-9) << "step " << s.step;
      const double a = angle(sim);
      if (a_prev > a && a_prev > a_prev2 && a_prev > 0) {  // a local maximum one step back
        peak = a_prev;
        t_peak = sim.time() - h;
      }
      a_prev2 = a_prev;
      a_prev = a;
    }
    const double ratio = peak / theta0;
    if (integrator == "backward_euler") {
      const double predicted = std::pow(1 + z * z, -t_peak / (2 * h));
      std::printf("BE: amplitude at t = %.2f s is %.4f of θ₀, predicted %.4f\n", t_peak, ratio, predicted);
      EXPECT_NEAR(ratio / predicted, 1.0, 0.02);
    } else {
      std::printf("BDF-2: amplitude at t = %.2f s is %.5f of θ₀\n", t_peak, ratio);
      EXPECT_GT(ratio, 0.995);
    }
  }
}

namespace {

/// A damped pendulum (joint kind `kind`, damping c on the joint) over 4 s: its amplitude ratio
/// at the last swing peak must follow exp(−c t / (2 I_pivot)) within 1 % and fall as c grows.
void expect_viscous_decay(const std::string& kind) {
  const double L = 1.0, theta0 = 0.1, h = 0.01, I = 0.01 / 6 + L * L;
  double previous_ratio = 2;
  for (const double c : {0.0, 0.05, 0.2, 0.5}) {
    Simulation sim = simulate(pendulum(kind, "bdf2", h, 4, L, theta0, R"(, "damping": )" + std::to_string(c)));
    double peak = 0, t_peak = 0, a_prev2 = 0, a_prev = angle(sim);
    while (sim.time() < 4 - 1e-9) {
      const StepStats s = sim.step();
      ASSERT_TRUE(s.newton.converged) << s.newton.failure;
      ASSERT_LT(s.joint_error, 1e-9);
      const double a = angle(sim);
      if (a_prev > a && a_prev > a_prev2 && a_prev > 0) {
        peak = a_prev;
        t_peak = sim.time() - h;
      }
      a_prev2 = a_prev;
      a_prev = a;
    }
    const double ratio = peak / theta0, predicted = std::exp(-c * t_peak / (2 * I));
    std::printf("%s damping c = %.2f N·m·s/rad: amplitude at t = %.2f s is %.4f of θ₀, exp(−c t/2I) = %.4f\n",
                kind.c_str(), c, t_peak, ratio, predicted);
    EXPECT_NEAR(ratio / predicted, 1.0, 0.01);
    EXPECT_LT(ratio, previous_ratio);
    previous_ratio = ratio;
  }
}

}  // namespace

TEST(Pendulum, JointDampingDecaysAsAViscousDamper) {
  // A hinge damper c (N·m·s/rad) on I_pivot θ̈ = −m g L θ − c θ̇ decays the amplitude as
  // exp(−c t / (2 I_pivot)); BDF-2 with h = 1e-2 adds ≈ 1e-4 of its own. More c, less amplitude.
  expect_viscous_decay("hinge");
}

TEST(Pendulum, BallJointDampingDecaysAsAViscousDamper) {
  // A ball-joint damper c damps the bob's angular velocity relative to the world: a torque
  // −c ω, so the planar swing obeys the same I_pivot θ̈ = −m g L θ − c θ̇ as the hinge above, and
  // its peaks (at t = kπ/ω_d for a release at rest) lie on exp(−c t / (2 I_pivot)). Errors:
  // BDF-2's own decay ≈ 1e-4 at h = 1e-2, the peak's time known to a step, the affine body's
  // slight non-rigidity in ω = ½ Σ f_k × ḟ_k: well inside 1 %.
  expect_viscous_decay("ball");
}

TEST(ContactDamping, BounceHeightDecreasesAsKdGrows) {
  // A cube dropped 0.2 m onto a fixed slab under BDF-2: the rebound apex falls as k_d grows
  // (measured: 0.159, 0.156, 0.134, 0.041, 0.0015 m).
  double previous = 1e9;
  for (const double k_d : {0.0, 1e-7, 1e-6, 1e-5, 1e-4}) {
    Simulation sim = simulate(R"({"description": "bounce", "time": {"dt": 0.005, "integrator": "bdf2"},
      "contact": {"dhat": 1e-3, "damping": )" + num(k_d) + R"(},
      "bodies": [{"name": "slab", "kind": "fixed", "mesh": {"primitive": "box", "size": [1, 0.1, 1]}, "position": [0, -0.05, 0]},
                 {"name": "cube", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, 0.25, 0]}]})");
    const int dof = sim.model().bodies[1].dof;
    bool bounced = false;
    double apex = 0, v_prev = 0;
    for (int k = 0; k < 200; ++k) {
      const StepStats s = sim.step();
      ASSERT_TRUE(s.newton.converged) << s.newton.failure;
      const double v = sim.qdot()[dof + 1];
      if (v_prev < 0 && v > 0) bounced = true;
      if (bounced) apex = std::max(apex, sim.q()[dof + 1] - 0.05);
      if (bounced && v < 0 && v_prev >= 0) break;  // past the apex
      v_prev = v;
    }
    std::printf("contact damping k_d = %g s: rebound apex %.4f m of 0.2 m (e = %.3f)\n", k_d, apex,
                std::sqrt(std::max(apex, 0.0) / 0.2));
    EXPECT_LT(apex, previous);
    previous = apex;
  }
}

TEST(ContactDamping, PairDampingActsOnItsPairOnly) {
  // Two cubes dropped side by side onto a slab under BDF-2; contact.pairs damps cube a with the
  // slab only (k_d = 1e-4 s, which alone takes a single cube's rebound from 0.159 m to 0.0015 m,
  // test above). Cube b must rebound as with no damping at all (the two share only Newton's
  // iteration count, so within 1 %), cube a far lower.
  const auto apexes = [](const std::string& pairs) {
    Simulation sim = simulate(R"({"description": "pair damping", "time": {"dt": 0.005, "integrator": "bdf2"},
      "contact": {"dhat": 1e-3, "pairs": [)" + pairs + R"(]},
      "bodies": [{"name": "slab", "kind": "fixed", "mesh": {"primitive": "box", "size": [1, 0.1, 1]}, "position": [0, -0.05, 0]},
                 {"name": "a", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [-0.25, 0.25, 0]},
                 {"name": "b", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0.25, 0.25, 0]}]})");
    std::array<double, 2> apex{0, 0};
    std::array<bool, 2> bounced{false, false};
    std::array<double, 2> v_prev{0, 0};
    for (int k = 0; k < 130; ++k) {  // 0.65 s: past both apexes
      const StepStats s = sim.step();
      EXPECT_TRUE(s.newton.converged) << s.newton.failure;
      for (int i = 0; i < 2; ++i) {
        const int dof = sim.model().bodies[1 + i].dof;
        const double v = sim.qdot()[dof + 1];
        if (v_prev[i] < 0 && v > 0) bounced[i] = true;
        if (bounced[i]) apex[i] = std::max(apex[i], sim.q()[dof + 1] - 0.05);
        v_prev[i] = v;
      }
    }
    return apex;
  };
  const std::array<double, 2> none = apexes(""), damped = apexes(R"({"body_a": "slab", "body_b": "a", "damping": 1e-4})");
  std::printf("pair damping: rebound apex a %.4f m (undamped %.4f m), b %.4f m (undamped %.4f m)\n", damped[0], none[0],
              damped[1], none[1]);
  EXPECT_GT(none[0], 0.1);
  EXPECT_NEAR(none[0], none[1], 0.01 * none[1]);  // the scene is symmetric
  EXPECT_NEAR(damped[1], none[1], 0.01 * none[1]);
  EXPECT_LT(damped[0], 0.1 * none[0]);
}

TEST(JointLimits, HingeRotationRangeIsNeverCrossed) {
  // A pendulum released 60° from the vertical with a lower rotation limit of −0.5 rad: it hits
  // the limit barrier, and its angle stays above the limit at every step.
  const double theta0 = M_PI / 3, lower = -0.5;
  // κ = 1 J as when this test was written: with the automatic κ (1.70 J here) one step (t =
  // 0.71 s) stalls at 1.8e-8 m/s against this test's 1e-8 m/s tolerance (the PSD-projected
  // angle Hessian converges linearly near round-off); 1.5, 2 and 3 J converge.
  Simulation sim = simulate(pendulum("hinge", "bdf2", 0.01, 2, 0.5, theta0,
                                     R"(, "lower": -0.5, "upper": 0.3, "limit_activation": 0.05, "limit_stiffness": 1)"));
  double smallest_gap = 1e9;
  for (int k = 0; k < 150; ++k) {
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged) << s.newton.failure;
    ASSERT_LT(s.joint_error, 1e-9);
    // The hinge's own angle measure (the one the barrier keeps above the limit).
    const auto& [limit, vectors] = sim.joint_term().potentials().at(0);
    ASSERT_EQ(limit.wrap, JointWrap::LowerBarrier);
    const double theta = measure(limit.measure, vectors.gather(sim.q()));
    ASSERT_GT(theta, lower) << "step " << s.step;
    // The bob's centre agrees with it up to the affine body's small non-rigidity.
    EXPECT_NEAR(angle(sim) - theta0, theta, 1e-3);
    smallest_gap = std::min(smallest_gap, theta - lower);
  }
  std::printf("hinge limit: smallest gap to the lower limit %.3e rad\n", smallest_gap);
  EXPECT_LT(smallest_gap, 0.05);  // the barrier was active: the limit stopped the swing
}

TEST(JointLimits, ConeTwistSwingAndTwistAreNeverExceeded) {
  // A bob hanging 0.5 m below a world cone-twist joint (axis along the rod), pushed at 1.72 m/s
  // (free, it would swing to 0.8 rad) and spun at 2 rad/s about the rod: the swing limit
  // (0.3 rad) and the twist range (±0.2 rad) stop it, and are never exceeded.
  const double L = 0.5, v = 1.72, swing = 0.3, twist = 0.2;
  Simulation sim = simulate(R"({"description": "cone", "time": {"dt": 0.01, "integrator": "bdf2"},
    "solver": {"tolerance": 1e-6},
    "bodies": [{"name": "bob", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, )" + num(-L) + R"(, 0],
                "velocity": [)" + num(v) + R"(, 0, 0], "angular_velocity": [0, 2, )" + num(v / L) + R"(]}],
    "joints": [{"name": "shoulder", "kind": "cone_twist", "body_a": "bob", "anchor": [0, 0, 0], "axis": [0, -1, 0],
                "swing": )" + num(swing) + R"(, "twist_lower": )" + num(-twist) + R"(, "twist_upper": )" + num(twist) + R"(}]})");
  const auto value_of = [&](JointMeasure kind) {
    for (const auto& [p, vectors] : sim.joint_term().potentials())
      if (p.measure == kind) return measure(kind, vectors.gather(sim.q()));
    return std::nan("");
  };
  double largest_bend = 0, largest_twist = 0;
  for (int k = 0; k < 150; ++k) {
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged) << s.newton.failure;
    ASSERT_LT(s.joint_error, 1e-9);
    const double bend = value_of(JointMeasure::BendAngle), tw = value_of(JointMeasure::TwistAngle);
    ASSERT_LT(bend, swing) << "step " << s.step;
    ASSERT_LT(std::abs(tw), twist) << "step " << s.step;
    largest_bend = std::max(largest_bend, bend);
    largest_twist = std::max(largest_twist, std::abs(tw));
  }
  std::printf("cone-twist: largest bend %.4f rad (swing %.2f), largest |twist| %.4f rad (range ±%.2f)\n", largest_bend,
              swing, largest_twist, twist);
  EXPECT_GT(largest_bend, swing - 0.05);  // the barriers were active: the limits stopped it
  EXPECT_GT(largest_twist, twist - 0.05);
}

TEST(JointLimits, PrismaticSlidesAlongItsAxisWithinItsRange) {
  // A cube on a world prismatic joint along a 30° rail slides down under gravity until the
  // sliding range stops it; it stays on the axis (penalty) and inside the range.
  const double angle_rad = M_PI / 6;
  const Eigen::Vector3d axis(std::cos(angle_rad), -std::sin(angle_rad), 0);
  Simulation sim = simulate(R"({"description": "slider", "time": {"dt": 0.01, "integrator": "bdf2"},
    "solver": {"tolerance": 1e-6},
    "bodies": [{"name": "cube", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}}],
    "joints": [{"name": "rail", "kind": "prismatic", "body_a": "cube", "anchor": [0, 0, 0],
                "axis": [)" + std::to_string(axis.x()) + ", " + std::to_string(axis.y()) + R"(, 0],
                "stiffness": 1e6, "lower": -0.05, "upper": 0.3, "limit_activation": 0.02}]})");
  double largest = -1;
  for (int k = 0; k < 100; ++k) {
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged) << s.newton.failure;
    const Eigen::Vector3d p = sim.q().head<3>();
    const double slide = p.dot(axis), off = (p - slide * axis).norm();
    ASSERT_LT(slide, 0.3) << "step " << s.step;
    ASSERT_GT(slide, -0.05);
    // Off-axis drift: the penalty holds the normal weight m g cos 30° = 8.5 N at k = 1e6 N/m.
    EXPECT_LT(off, 2e-5) << "step " << s.step;
    EXPECT_LT(abd::orthogonality_error(sim.q().head<12>()), 1e-6);  // orientation locked exactly
    largest = std::max(largest, slide);
    if (k == 30) {
      // Free sliding so far: s = ½ g sin 30° t² while away from the limit.
      EXPECT_NEAR(slide, std::min(0.5 * kG * 0.5 * 0.31 * 0.31, 0.3), 0.03);
    }
  }
  std::printf("prismatic: largest slide %.5f m (limit 0.3 m)\n", largest);
  EXPECT_GT(largest, 0.25);
}

TEST(SpinningTop, PrecessesAtTheGyroscopicRate) {
  // A disc (r = 0.1 m, 2 cm thick) on a massless stick, its tip on a world ball joint 0.1 m
  // below the centre, tilted 25°, spinning at ω₃ about its axis and started on its steady
  // precession. Gyroscopic formula: Ω = m g d / (I₃ ω₃). BDF-2 takes ≈ (ω h)⁴ of an affine
  // body's spin energy per step (h = 1e-3 at ω₃ = 200 lost 23 % of the spin in 0.6 s), so the
  // step keeps ω₃ h = 0.05.
  for (const double spin : {100.0, 200.0}) {
    const double h = 0.05 / spin;
    const double tilt = 25 * M_PI / 180, d = 0.1;
    const Eigen::Vector3d e3(std::sin(tilt), std::cos(tilt), 0);  // axis tilted toward +x
    const Eigen::Vector3d centre = d * e3;
    // I₃ of the 32-gon prism ≈ m r²/2 for the initial ω; the check uses the model's exact value.
    const double m_guess = M_PI * 0.01 * 0.02 * 1000, omega_guess = m_guess * kG * d / (m_guess * 0.01 / 2 * spin);
    const Eigen::Vector3d w = spin * e3 + omega_guess * Eigen::Vector3d::UnitY();
    Simulation sim = simulate(R"({"description": "top", "time": {"dt": )" + num(h) + R"(, "integrator": "bdf2"},
      "solver": {"tolerance": 1e-6},
      "bodies": [{"name": "top", "mesh": {"primitive": "cylinder", "radius": 0.1, "height": 0.02, "resolution": 32},
                  "position": [)" + std::to_string(centre.x()) + ", " + std::to_string(centre.y()) + R"(, 0],
                  "rotation_deg": [0, 0, )" + std::to_string(-tilt * 180 / M_PI) + R"(],
                  "angular_velocity": [)" + std::to_string(w.x()) + ", " + std::to_string(w.y()) + ", " +
                              std::to_string(w.z()) + R"(]}],
      "joints": [{"name": "tip", "kind": "ball", "body_a": "top", "anchor": [0, 0, 0]}]})");
    const BodyModel& top = sim.model().bodies[0];
    const Eigen::Matrix3d S = top.M.block<3, 3>(3, 3);
    const double I3 = S.trace() - S(1, 1);  // about the body-frame y axis
    const double Omega = top.mass * kG * d / (I3 * spin);
    const auto azimuth = [&] {
      const Eigen::Vector3d axis = abd::affine_matrix(sim.q().head<12>()) * Eigen::Vector3d::UnitY();
      return std::atan2(axis.z(), axis.x());
    };
    const double phi0 = azimuth();
    double phi = phi0, previous = phi0;
    const double duration = 0.6;
    while (sim.time() < duration - 1e-9) {
      const StepStats s = sim.step();
      ASSERT_TRUE(s.newton.converged) << s.newton.failure;
      ASSERT_LT(s.joint_error, 1e-9);
      double a = azimuth();
      while (a - previous > M_PI) a -= 2 * M_PI;
      while (a - previous < -M_PI) a += 2 * M_PI;
      phi += a - previous;
      previous = a;
    }
    const double measured = -(phi - phi0) / sim.time();  // precession about +y
    const Eigen::Vector3d axis = abd::affine_matrix(sim.q().head<12>()) * Eigen::Vector3d::UnitY();
    const double spin_end = abd::angular_velocity(sim.q().head<12>(), sim.qdot().head<12>()).dot(axis.normalized());
    std::printf("top ω₃ = %.0f rad/s (h = %.2g s, spin at the end %.2f): precession %.4f rad/s, gyroscopic m g d/(I₃ ω₃) = "
                "%.4f (%.2f %%)\n", spin, h, spin_end, measured, Omega, 100 * (measured / Omega - 1));
    EXPECT_NEAR(measured / Omega, 1.0, 0.05);
  }
}

TEST(SoftPin, AffineBodyHangsFromASoftBodysNode) {
  // A 10 cm affine cube hangs on a ball joint from the bottom node of a soft block whose top
  // nodes are fixed: the pin (a linear equality with the node's 3 DOFs) holds at every step
  // and the block sags under the cube.
  Simulation sim = simulate(R"({"description": "soft pin", "time": {"dt": 0.01, "integrator": "bdf2"},
    "bodies": [{"name": "block", "model": "soft", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]},
                "mesh_size": 0.1, "material": {"young": 1e5, "poisson": 0.3}, "position": [0, 0.3, 0],
                "dirichlet": [{"select": "box", "min": [-1, 0.39, -1], "max": [1, 1, 1]}]},
               {"name": "cube", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, 0.1, 0]}],
    "joints": [{"name": "pin", "kind": "ball", "body_a": "cube", "body_b": "block", "anchor": [0, 0.2, 0]}]})");
  const JointModel& pin = sim.model().joints.at(0);
  ASSERT_GE(pin.b.node, 0);
  const double y0 = sim.model().nodes.X(pin.b.node, 1);
  for (int k = 0; k < 20; ++k) {
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged) << s.newton.failure;
    ASSERT_LT(s.joint_error, 1e-9) << "step " << s.step;
  }
  const double y = sim.node_positions()(pin.b.node, 1);
  std::printf("soft pin: node moved %.3e m down; joint force %.3f N (cube weight %.3f N)\n", y0 - y,
              sim.joint_forces()[0].norm(), sim.model().bodies[1].mass * kG);
  EXPECT_GT(y0 - y, 1e-5);
}

TEST(SoftPin, BlockGluedToSeveralNodesHoldsEveryPinAndDropsRedundantRows) {
  // An affine cube glued (nodes_within) under a soft block's top face, whose nodes are all
  // fixed: every node within 0.15 m of the face's centre is pinned to the cube, 3 rows each.
  // The fixed nodes are coplanar, so their rows fix only 9 of the cube's 12 DOFs and most of
  // them are combinations of others: the elimination must drop them as redundant, and the
  // cube, held by the fixed face, stays where it is while the pins hold at every step.
  Simulation sim = simulate(R"({"description": "glue", "time": {"dt": 0.01, "integrator": "bdf2"},
    "bodies": [{"name": "block", "model": "soft", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]},
                "mesh_size": 0.1, "material": {"young": 1e5, "poisson": 0.3}, "position": [0, 0.3, 0],
                "dirichlet": [{"select": "box", "min": [-1, 0.39, -1], "max": [1, 1, 1]}]},
               {"name": "cube", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, 0.46, 0]}],
    "joints": [{"name": "glue", "kind": "ball", "body_a": "cube", "body_b": "block", "anchor": [0, 0.4, 0],
                "nodes_within": 0.15}]})");
  const JointModel& glue = sim.model().joints.at(0);
  int fixed = 0;
  for (const NodePin& pin : glue.pins) fixed += sim.model().nodes.block[pin.node] < 0;
  fixed += sim.model().nodes.block[glue.b.node] < 0;
  const int rows = sim.joint_constraints().rows();
  EXPECT_EQ(rows, 3 * (1 + int(glue.pins.size())));
  ASSERT_NE(sim.reduced_basis(), nullptr);
  const int redundant = int(sim.reduced_basis()->redundant_rows().size());
  std::printf("glue: %zu nodes pinned (%d fixed), %d rows, %d redundant\n", glue.pins.size() + 1, fixed, rows, redundant);
  EXPECT_GE(fixed, 4);
  EXPECT_GE(redundant, 3 * fixed - 9);  // coplanar fixed points fix at most 9 affine DOFs
  const Eigen::Vector3d p0 = sim.q().segment<3>(sim.model().bodies[1].dof);
  for (int k = 0; k < 20; ++k) {
    const StepStats s = sim.step();
    ASSERT_TRUE(s.newton.converged) << s.newton.failure;
    ASSERT_LT(s.joint_error, 1e-9) << "step " << s.step;
  }
  const Eigen::Vector3d p = sim.q().segment<3>(sim.model().bodies[1].dof);
  std::printf("glue: cube moved %.3e m in 0.2 s\n", (p - p0).norm());
  EXPECT_LT((p - p0).norm(), 1e-3);
}

TEST(JointForces, HangingPendulumCarriesItsWeight) {
  // At rest below its pivot, the bob's ball joint holds exactly its weight m g (upwards).
  Simulation sim = simulate(pendulum("ball", "backward_euler", 0.01, 1, 1.0, 0.0));
  for (int k = 0; k < 5; ++k) ASSERT_TRUE(sim.step().newton.converged);
  const Eigen::Vector3d f = sim.joint_forces().at(0);
  const double weight = sim.model().bodies[0].mass * kG;
  std::printf("hanging pendulum: joint force (%.4f, %.4f, %.4f) N, weight %.4f N\n", f.x(), f.y(), f.z(), weight);
  EXPECT_NEAR(f.y(), weight, 1e-3 * weight);
  EXPECT_LT(std::hypot(f.x(), f.z()), 1e-3 * weight);
}

TEST(JointForces, HangingPendulumsParaViewFrameCarriesItsWeight) {
  // `stiffsoft run` writes the joints as PolyData beside the bodies' frames: the pivot's two
  // ends at the origin, its force on the bob m g upwards, no limit (gap NaN).
  const std::filesystem::path out = stiffsoft::testing::temporary_folder("stiffsoft_joint_vtp");
  {
    std::ofstream scene(out / "hang.json");
    scene << pendulum("ball", "backward_euler", 0.01, 1, 1.0, 0.0);
  }
  ASSERT_EQ(stiffsoft::testing::run_stiffsoft("run " + (out / "hang.json").string() + " -o " + (out / "o").string() +
                                                  " --steps 5",
                                              out / "run.log"),
            0)
      << stiffsoft::testing::read_text(out / "run.log");
  const std::string pvd = stiffsoft::testing::read_text(out / "o" / "hang_joints.pvd");
  std::size_t frames = 0;
  for (std::size_t at = pvd.find("<DataSet"); at != std::string::npos; at = pvd.find("<DataSet", at + 1)) ++frames;
  ASSERT_GE(frames, 2u) << pvd;
  char name[64];
  std::snprintf(name, sizeof(name), "hang_joints_%06zu.vtp", frames - 1);
  const JointFrameRead frame = read_joint_frame(out / "o" / "frames" / name);
  EXPECT_NEAR(frame.time, 0.05, 1e-12);
  ASSERT_EQ(frame.joints.size(), 1u);
  const JointFrameEntry& pivot = frame.joints[0];
  EXPECT_EQ(pivot.name, "pivot");
  EXPECT_EQ(pivot.kind, int(JointKind::Ball));
  EXPECT_LT(pivot.x_a.norm(), 1e-9);
  EXPECT_LT(pivot.x_b.norm(), 1e-9);
  const double weight = 1000 * 1e-3 * kG;
  std::printf("hanging pendulum (ParaView frame): force (%.4f, %.4f, %.4f) N, weight %.4f N\n", pivot.force.x(),
              pivot.force.y(), pivot.force.z(), weight);
  EXPECT_NEAR(pivot.force.y(), weight, 1e-3 * weight);
  EXPECT_LT(std::hypot(pivot.force.x(), pivot.force.z()), 1e-3 * weight);
  EXPECT_TRUE(std::isnan(pivot.gap));
  std::filesystem::remove_all(out);
}

TEST(JointScene, LimitStiffnessDefaultsToBodyAsEnergyScale) {
  // κ = m_a (|g| ℓ_a + ½ v_a²): a 1 kg cube of side 0.1 m (ℓ = 0.1 √3 m) at rest weighs in at
  // m g ℓ = 1.699 J; pushed at 2 m/s it adds ½ m v² = 2 J; an explicit value wins.
  const auto kappa = [](const std::string& extra_body, const std::string& extra_joint) {
    Simulation sim = simulate(R"({"description": "kappa",
      "bodies": [{"name": "bob", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, -1, 0])" +
                              extra_body + R"(}],
      "joints": [{"name": "pivot", "kind": "hinge", "body_a": "bob", "anchor": [0, 0, 0], "lower": -1, "upper": 1)" +
                              extra_joint + "}]}");
    return sim.model().joints.at(0).limit_stiffness;
  };
  const double m_g_l = 1.0 * kG * 0.1 * std::sqrt(3.0);
  EXPECT_NEAR(kappa("", ""), m_g_l, 1e-9);
  EXPECT_NEAR(kappa(R"(, "velocity": [2, 0, 0])", ""), m_g_l + 2.0, 1e-9);
  EXPECT_EQ(kappa("", R"(, "limit_stiffness": 7.5)"), 7.5);
}

TEST(JointScene, ErrorsNameTheJointAndWhatWasExpected) {
  const auto error_of = [](const std::string& joint) -> std::string {
    try {
      simulate(R"({"description": "bad joint",
        "bodies": [{"name": "a", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}},
                   {"name": "wall", "kind": "fixed", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [1, 0, 0]}],
        "joints": [)" + joint + "]}");
    } catch (const std::exception& e) {
      return e.what();
    }
    return "no error";
  };
  const auto expect = [&](const std::string& joint, const std::vector<std::string>& needles) {
    const std::string message = error_of(joint);
    for (const std::string& n : needles) EXPECT_NE(message.find(n), std::string::npos) << "'" << n << "' not in: " << message;
  };
  expect(R"({"name": "j", "kind": "ball", "body_a": "nobody", "anchor": [0, 0, 0]})", {"joints[0].body_a", "nobody"});
  expect(R"({"name": "j", "kind": "ball", "body_a": "a", "body_b": "a", "anchor": [0, 0, 0]})", {"joints[0].body_b", "differ"});
  expect(R"({"name": "j", "kind": "ball", "body_a": "wall", "anchor": [0, 0, 0]})", {"joints[0].body_a", "fixed"});
  expect(R"({"name": "j", "kind": "hinge", "body_a": "a", "anchor": [0, 0, 0], "lower": 0.2})", {"joints[0].lower", "< 0"});
  expect(R"({"name": "j", "kind": "hinge", "body_a": "a", "anchor": [0, 0, 0], "upper": 4})", {"joints[0].upper", "π"});
  expect(R"({"name": "j", "kind": "distance", "body_a": "a", "anchor": [0, 0, 0]})", {"joints[0].anchor_b", "required"});
  expect(R"({"name": "j", "kind": "bounded_distance", "body_a": "a", "anchor": [0, 0, 0], "anchor_b": [0, 1, 0], "upper": 0.5})",
         {"joints[0]", "initial distance"});
  expect(R"({"name": "j", "kind": "ball", "body_a": "a", "anchor": [0, 0, 0], "swing": 1})", {"joints[0].swing", "only allowed"});
  expect(R"({"name": "j", "kind": "cone_twist", "body_a": "a", "anchor": [0, 0, 0], "swing": 3.2})", {"joints[0].swing", "< π"});
  expect(R"({"name": "j", "kind": "cone_twist", "body_a": "a", "anchor": [0, 0, 0], "twist_upper": 0.5})",
         {"joints[0].swing", "required", "bend π"});
  expect(R"({"name": "j", "kind": "cone_twist", "body_a": "a", "anchor": [0, 0, 0], "swing": 1, "twist_lower": 0.1})",
         {"joints[0].twist_lower", "< 0"});
  expect(R"({"name": "j", "kind": "ball", "body_a": "a", "body_b": "wall", "anchor": [0, 0, 0], "nodes_within": 0.1})",
         {"joints[0].nodes_within", "soft"});
  expect(R"({"name": "j", "kind": "ball", "body_a": "a", "anchor": [0, 0, 0]}, {"name": "j", "kind": "ball", "body_a": "a", "anchor": [0, 0, 0]})",
         {"joints[1].name", "duplicate"});
}

TEST(DistanceJoints, PenaltyKeepsTheLengthAndTheRopeNeverOverstretches) {
  // A 1 kg cube swinging from a world point 0.3 m away, on a distance joint (k = 1e5 N/m: the
  // length moves by tension / k, at most ≈ 3 m g / k = 3e-4 m) and on a rope (bounded_distance,
  // upper 0.5 m: it falls free, then the rope catches it and never passes 0.5 m).
  for (const std::string kind : {"distance", "bounded_distance"}) {
    const std::string extra = kind == "distance" ? R"("stiffness": 1e5)" : R"("upper": 0.5, "limit_activation": 0.02)";
    Simulation sim = simulate(R"({"description": "rope", "time": {"dt": 0.005, "integrator": "bdf2"},
      "solver": {"tolerance": 1e-6},
      "bodies": [{"name": "bob", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0.3, 0, 0]}],
      "joints": [{"name": "rope", "kind": ")" + kind + R"(", "body_a": "bob", "anchor": [0.3, 0, 0],
                  "anchor_b": [0, 0, 0], )" + extra + "}]}");
    double shortest = 1e9, longest = 0;
    for (int k = 0; k < 200; ++k) {
      const StepStats s = sim.step();
      ASSERT_TRUE(s.newton.converged) << kind << " step " << s.step << ": " << s.newton.failure;
      const double length = sim.q().head<3>().norm();
      shortest = std::min(shortest, length);
      longest = std::max(longest, length);
      if (kind == "bounded_distance") ASSERT_LT(length, 0.5) << "step " << s.step;
    }
    std::printf("%s: length between %.6f and %.6f m\n", kind.c_str(), shortest, longest);
    if (kind == "distance") {
      EXPECT_NEAR(shortest, 0.3, 5e-4);
      EXPECT_NEAR(longest, 0.3, 5e-4);
    } else {
      EXPECT_GT(longest, 0.48);  // the rope went taut
    }
  }
}
