/// @file Hertz contact (validation.md, issue 3): the lower half of a linear-elastic sphere,
/// R = 0.05 m, whose flat top is driven down slowly (a Dirichlet velocity), pressed onto a fixed
/// affine plane through the IPC barrier with d̂ = 1e-5 m. The total contact force F against the
/// indentation δ must follow F = (4/3) E* √R δ^{3/2}, E* = E / (1 − ν²), within 5 % at the finest
/// mesh used. docs/validation_hertz.md has the measured tables.
///
/// What δ is. Hertz's δ is the approach of the contact point and points far away in a half-space,
/// where the displacement vanishes. A finite body has no such points: the half-space solution
/// itself still moves the top of the cap, R above the contact, by ≈ (1+ν)(3−2ν) F / (2π E R)
/// (5–7 % of δ here), and the cap's own bulk compliance and clamped top add to it, all of relative
/// size ∝ a/R. So "prescribed displacement minus gap" (the shortening of the whole cap) is not
/// Hertz's δ; it is printed as err_top (8–15 % off) but not tested. δ is measured locally:
/// w_d, the shortening of the axis between the pole (the contact point) and a node embedded on the
/// axis at depth d, plus what the half-space solution puts below that depth, which is analytic:
///   δ = w_d + [δ_H(F) − w_d^H(F)],
///   w_d^H = (1+ν) p₀ a / E · [atan T − 2ν (T/2 − (T²+1)/2 · acot T + π/4)],  T = d / a,
/// the axial strain ε_z = (σ_z − 2ν σ_r) / E of Hertz's on-axis stresses integrated from 0 to d
/// (it tends to δ_H as d → ∞; HertzAnalytic checks both). The cap's finite size then enters only
/// through the regular part of its stress field over the depth d, a relative error of order
/// a d / R² (≤ 2 % at d = 10 mm). δ from the nodes at 5 and 10 mm agree within 0.7 % (0.1 % on the fine
/// mesh), which bounds that error; the 20 mm node lies where the mesh has coarsened to ≈ 6 mm.
///
/// Why ν = 0.3 and a linear material: Hertz's theory is linear elasticity; linear tetrahedra
/// stiffen (lock) as ν → 0.5, a discretisation error unrelated to contact (ν = 0.45 measured in
/// the doc). Quasi-static: backward Euler with the top face moving 50 µm per step; 25 µm per
/// step gave the same errors to 0.01 %.
///
/// The suite runs the coarse mesh (≈ 30 s on two busy cores); STIFFSOFT_LONG_TESTS=1 runs the
/// refinement study (coarse, mid, fine; ≈ 5 min).

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "scene_helpers.hpp"

using namespace stiffsoft;
using namespace stiffsoft::testing;

namespace {

constexpr double kR = 0.05;        // sphere radius (m)
constexpr double kE = 1e6;         // Young's modulus (Pa)
constexpr double kNu = 0.3;        // Poisson ratio
constexpr double kEstar = kE / (1 - kNu * kNu);  // Pa
constexpr double kDhat = 1e-5;     // barrier activation distance d̂ (m)
constexpr double kGap0 = 2e-5;     // initial gap between the pole and the plane (m), > d̂
constexpr double kDt = 0.01;       // time step (s)
constexpr double kSpeed = 5e-3;    // speed of the top face (m/s): 50 µm per step
constexpr double kDepths[3] = {0.005, 0.010, 0.020};  // axis nodes embedded by the .geo files (m)
constexpr int kMainDepth = 1;                         // δ from the 10 mm node is the one tested
constexpr double kDeltaMin = 0.15e-3, kDeltaMax = 0.5e-3;  // load levels compared (m): a = 2.7–5 mm
constexpr double kHertzTolerance = 0.05;  // issue 3: within 5 % at the finest mesh used
// Fitted exponent of F against δ over the load levels: measured 1.481 (coarse), 1.489 (mid),
// 1.494 (fine); a bulk-dominated (linear spring) response would give 1.
constexpr double kExponentTolerance = 0.03;

/// Hertz's force at indentation δ (N).
double hertz_force(double delta) { return 4.0 / 3.0 * kEstar * std::sqrt(kR) * std::pow(delta, 1.5); }

/// Hertz's indentation at force F (m).
double hertz_delta(double F) { return std::pow(3 * F / (4 * kEstar * std::sqrt(kR)), 2.0 / 3.0); }

/// Hertz's contact radius a and peak pressure p₀ at force F (m, Pa).
std::pair<double, double> hertz_radius_and_pressure(double F) {
  const double a = std::cbrt(3 * F * kR / (4 * kEstar));
  return {a, 3 * F / (2 * std::numbers::pi * a * a)};
}

/// Shortening w_d^H of the axis between the surface and depth d (m) in a half-space under the
/// Hertz pressure of total force F: (1+ν) p₀ a / E ∫₀^{d/a} [1/(1+t²) − 2ν (1 − t acot t)] dt.
double hertz_axis_shortening(double F, double d) {
  const auto [a, p0] = hertz_radius_and_pressure(F);
  const double T = d / a;
  const double acot = std::atan2(1.0, T);
  const double integral = std::atan(T) - 2 * kNu * (T / 2 - (T * T + 1) / 2 * acot + std::numbers::pi / 4);
  return (1 + kNu) * p0 * a / kE * integral;
}

/// One step of a run, in contact.
struct Sample {
  double F = 0;               ///< total contact force on the cap, upwards (N)
  double F_plane = 0;         ///< total contact force on the plane, downwards (N)
  double shortening[3] = {};  ///< w_d: axis shortening pole → depth kDepths[i] (m)
  double delta[3] = {};       ///< δ from depth kDepths[i] (m), see the file comment
  double delta_top = 0;       ///< naive δ: shortening of the whole cap, pole → top face (m)
  double top_lag = 0;         ///< prescribed minus actual displacement of the top face, mean (m)
};

/// A run on one mesh.
struct HertzRun {
  std::string mesh;             ///< the .geo file
  int nodes = 0, tets = 0;      ///< mesh size
  std::vector<Sample> samples;  ///< one per step in contact
  bool converged = true;        ///< every Newton solve met its tolerance
  std::string failure;          ///< the first that did not
  int inverted = 0;             ///< largest inverted_tets over the steps
  int iterations = 0;           ///< Newton iterations, all steps
  double seconds = 0;           ///< wall time, meshing (or cache) included
  PhaseTimes times;             ///< phases, all steps
};

/// x with all its digits, for the JSON scene.
std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

/// The soft node at world position x (exactly: the .geo embeds it), or −1.
int node_at(const Model& model, const Eigen::Vector3d& x) {
  for (int i = 0; i < model.nodes.size(); ++i)
    if ((model.nodes.X.row(i).transpose() - x).norm() < 1e-9) return i;
  return -1;
}

/// Presses the cap meshed by `geo` (tests/apps/data/hertz/) until δ passes the largest load level.
HertzRun run_hertz(const std::string& geo) {
  const auto start = std::chrono::steady_clock::now();
  const double top = kGap0 + kR;
  // The plane's top face is split along a diagonal through its centre: the offset puts the
  // contact zone 42 mm from that edge. The cap starts at the top face's speed (no start jolt).
  const std::string json = R"({"description": "Hertz: a soft hemisphere pressed onto a fixed plane",
    "gravity": [0, 0, 0], "time": {"dt": )" + number(kDt) + R"(, "integrator": "backward_euler"},
    "contact": {"dhat": )" + number(kDhat) + R"(, "mu": 0},
    "solver": {"tolerance": 1e-5, "max_iterations": 100},
    "bodies": [
      {"name": "plane", "kind": "fixed", "mesh": {"primitive": "plane", "size": [0.3, 0.02, 0.3]},
       "position": [0.06, -0.01, 0]},
      {"name": "cap", "model": "soft", "mesh": "tests/apps/data/hertz/)" + geo + R"(", "mesh_size": 0.010,
       "material": {"model": "linear", "young": )" + number(kE) + R"(, "poisson": )" + number(kNu) + R"(},
       "position": [0, )" + number(kGap0) + R"(, 0], "velocity": [0, )" + number(-kSpeed) + R"(, 0],
       "dirichlet": [{"select": "half_space", "point": [0, )" + number(top - 1e-6) + R"(, 0], "normal": [0, 1, 0],
                      "velocity": [0, )" + number(-kSpeed) + R"(, 0]}]}]})";
  Simulation sim = simulate(json, "hertz");
  const Model& model = sim.model();
  HertzRun run;
  run.mesh = geo;
  run.nodes = model.nodes.size();
  run.tets = int(model.nodes.T.rows());
  const BodyModel& plane = model.bodies[0];
  const BodyModel& cap = model.bodies[1];

  const int pole = node_at(model, {0, kGap0, 0});
  int axis[3];
  for (int i = 0; i < 3; ++i) axis[i] = node_at(model, {0, kGap0 + kDepths[i], 0});
  EXPECT_GE(pole, 0) << geo << ": no node at the pole";
  for (int i = 0; i < 3; ++i) EXPECT_GE(axis[i], 0) << geo << ": no node on the axis at depth " << kDepths[i];
  std::vector<int> top_nodes;
  for (int i = 0; i < model.nodes.size(); ++i)
    if (model.nodes.X(i, 1) > top - 1e-6) top_nodes.push_back(i);
  if (pole < 0 || std::find(axis, axis + 3, -1) != axis + 3 || top_nodes.empty()) return run;

  for (int k = 0; k < 40; ++k) {
    const StepStats s = sim.step();
    run.iterations += s.newton.iterations;
    run.times.broad_phase += s.times.broad_phase;
    run.times.ccd += s.times.ccd;
    run.times.assembly += s.times.assembly;
    run.times.solve += s.times.solve;
    run.inverted = std::max(run.inverted, s.inverted_tets);
    if (!s.newton.converged) {
      run.converged = false;
      run.failure = "step " + std::to_string(s.step) + ": " + s.newton.failure;
      break;
    }
    if (s.contacts == 0) continue;
    const Eigen::MatrixX3d f = sim.contact_forces();
    const Eigen::MatrixX3d x = sim.node_positions();
    Sample sample;
    sample.F = f.middleRows(cap.vertex_begin, cap.vertex_end - cap.vertex_begin).col(1).sum();
    sample.F_plane = -f.middleRows(plane.vertex_begin, plane.vertex_end - plane.vertex_begin).col(1).sum();
    const auto shortening = [&](int i) {
      return (model.nodes.X(i, 1) - model.nodes.X(pole, 1)) - (x(i, 1) - x(pole, 1));
    };
    for (int i = 0; i < 3; ++i) {
      sample.shortening[i] = shortening(axis[i]);
      sample.delta[i] = sample.shortening[i] + hertz_delta(sample.F) - hertz_axis_shortening(sample.F, kDepths[i]);
    }
    for (const int i : top_nodes) {
      sample.delta_top += shortening(i) / double(top_nodes.size());
      sample.top_lag += (kSpeed * sim.time() - (model.nodes.X(i, 1) - x(i, 1))) / double(top_nodes.size());
    }
    run.samples.push_back(sample);
    if (sample.delta[kMainDepth] > kDeltaMax) break;
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

/// Relative error of the force against Hertz's at the sample's δ from depth kDepths[depth].
double force_error(const Sample& s, int depth) { return s.F / hertz_force(s.delta[depth]) - 1; }

/// Whether the sample's δ is in the compared range.
bool is_load_level(const Sample& s) {
  return s.delta[kMainDepth] >= kDeltaMin && s.delta[kMainDepth] <= kDeltaMax;
}

/// Samples in the compared load range.
std::vector<Sample> load_levels(const HertzRun& run) {
  std::vector<Sample> levels;
  for (const Sample& s : run.samples)
    if (is_load_level(s)) levels.push_back(s);
  return levels;
}

/// Least-squares slope of log F against log δ (from depth kDepths[kMainDepth]).
double fitted_exponent(const std::vector<Sample>& levels) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(levels.size());
  for (const Sample& s : levels) {
    const double lx = std::log(s.delta[kMainDepth]), ly = std::log(s.F);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// What a run measured over its load levels.
struct HertzSummary {
  double worst = 0;     ///< largest |F / F_Hertz(δ) − 1|
  double exponent = 0;  ///< fitted exponent of F against δ
};

/// Prints the run's table; returns its summary (zeros without load levels).
HertzSummary report(const HertzRun& run) {
  std::printf("\n%s: %d nodes, %d tets, %zu steps in contact, %d Newton iterations, %.1f s (broad phase %.1f, "
              "CCD %.1f, assembly %.1f, solve %.1f)\n",
              run.mesh.c_str(), run.nodes, run.tets, run.samples.size(), run.iterations, run.seconds,
              run.times.broad_phase, run.times.ccd, run.times.assembly, run.times.solve);
  std::printf("  %8s %8s | %8s %8s %8s | %8s %8s %8s %8s | %8s %8s\n", "F (N)", "a_H (mm)", "δ5 (mm)", "δ10 (mm)",
              "δ20 (mm)", "err5", "err10", "err20", "err_top", "w10/w10H", "δ_H (mm)");
  HertzSummary summary;
  for (const Sample& s : run.samples) {
    std::printf("%s %8.4f %8.3f | %8.4f %8.4f %8.4f | %+7.2f%% %+7.2f%% %+7.2f%% %+7.2f%% | %8.4f %8.4f\n",
                is_load_level(s) ? "*" : " ", s.F, 1e3 * hertz_radius_and_pressure(s.F).first, 1e3 * s.delta[0],
                1e3 * s.delta[1], 1e3 * s.delta[2], 100 * force_error(s, 0), 100 * force_error(s, 1),
                100 * force_error(s, 2), 100 * (s.F / hertz_force(s.delta_top) - 1),
                s.shortening[kMainDepth] / hertz_axis_shortening(s.F, kDepths[kMainDepth]), 1e3 * hertz_delta(s.F));
    if (is_load_level(s)) summary.worst = std::max(summary.worst, std::abs(force_error(s, kMainDepth)));
  }
  if (!run.samples.empty())
    std::printf("  top face at the end: %.2f µm behind its prescribed displacement\n", 1e6 * run.samples.back().top_lag);
  const std::vector<Sample> levels = load_levels(run);
  if (levels.size() < 2) return summary;
  summary.exponent = fitted_exponent(levels);
  double k_sum = 0, k_den = 0;  // F = k δ^{3/2}, least squares in F
  for (const Sample& s : levels) {
    const double x = std::pow(s.delta[kMainDepth], 1.5);
    k_sum += s.F * x, k_den += x * x;
  }
  const double k_hertz = 4.0 / 3.0 * kEstar * std::sqrt(kR);
  std::printf("  (* = load level) fitted exponent %.3f (Hertz 1.5); prefactor with exponent 1.5: %.4g N/m^1.5, "
              "Hertz %.4g (%+.2f %%); largest |error| at δ10: %.2f %%\n",
              summary.exponent, k_sum / k_den, k_hertz, 100 * (k_sum / k_den / k_hertz - 1), 100 * summary.worst);
  return summary;
}

/// Every step converged, no tet inverted, enough load levels, action = reaction.
void check_run(const HertzRun& run) {
  EXPECT_TRUE(run.converged) << run.mesh << ": " << run.failure;
  EXPECT_EQ(run.inverted, 0) << run.mesh << ": inverted tetrahedra";
  EXPECT_GE(load_levels(run).size(), 5u) << run.mesh << ": too few load levels in [0.15, 0.5] mm";
  for (const Sample& s : run.samples)
    EXPECT_NEAR(s.F, s.F_plane, 1e-9 * s.F) << run.mesh << ": the plane and the cap feel different forces";
}

/// Runs, checks and reports the meshes, coarsest first; asserts the criterion at the finest.
void refinement_study(const std::vector<std::string>& meshes) {
  std::vector<HertzSummary> summaries;
  for (const std::string& mesh : meshes) {
    const HertzRun run = run_hertz(mesh);
    check_run(run);
    summaries.push_back(report(run));
    EXPECT_NEAR(summaries.back().exponent, 1.5, kExponentTolerance) << mesh;
  }
  std::printf("\nlargest |F / F_Hertz(δ) − 1| over δ in [0.15, 0.5] mm:");
  for (size_t i = 0; i < meshes.size(); ++i) std::printf("  %s %.2f %%", meshes[i].c_str(), 100 * summaries[i].worst);
  std::printf("\n");
  for (size_t i = 1; i < meshes.size(); ++i)
    EXPECT_LT(summaries[i].worst, summaries[i - 1].worst) << meshes[i] << ": refining must reduce the error";
  EXPECT_GT(summaries.back().worst, 0.0) << "no load levels";
  EXPECT_LE(summaries.back().worst, kHertzTolerance) << meshes.back() << " (the finest mesh used)";
}

/// STIFFSOFT_LONG_TESTS=1: run the refinement study.
bool long_tests() {
  const char* v = std::getenv("STIFFSOFT_LONG_TESTS");
  return v && std::string(v) == "1";
}

}  // namespace

// The closed form of w_d^H against a midpoint-rule integral of Hertz's on-axis strain, and its
// limit d → ∞, which is δ_H = a² / R.
TEST(HertzAnalytic, AxisShorteningIntegratesTheOnAxisStrainAndTendsToTheIndentation) {
  for (const double F : {0.5, 4.0}) {
    const auto [a, p0] = hertz_radius_and_pressure(F);
    const double d = 0.01;
    const int n = 20000;
    double w = 0;
    for (int i = 0; i < n; ++i) {
      const double t = (i + 0.5) * d / n / a;
      const double sigma_z = -p0 / (1 + t * t);
      const double sigma_r = -p0 * ((1 + kNu) * (1 - t * std::atan(1 / t)) - 0.5 / (1 + t * t));
      w -= (sigma_z - 2 * kNu * sigma_r) / kE * d / n;
    }
    EXPECT_NEAR(hertz_axis_shortening(F, d), w, 1e-7 * w) << "F = " << F;
    EXPECT_NEAR(hertz_axis_shortening(F, 1e4), hertz_delta(F), 1e-6 * hertz_delta(F)) << "F = " << F;
    EXPECT_NEAR(hertz_delta(F), a * a / kR, 1e-12);
  }
}

TEST(Hertz, SphereOnPlaneForceIndentationWithinFivePercent) {
  if (long_tests())
    refinement_study({"cap_coarse.geo", "cap_mid.geo", "cap_fine.geo"});
  else
    refinement_study({"cap_coarse.geo"});
}
