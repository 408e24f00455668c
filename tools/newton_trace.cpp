/// @file newton_trace: one CSV row per Newton direction of a run (issue 17's diagnosis of the
/// steps' tails, docs/newton.md, session 36). It continues a run from its checkpoint (or starts
/// the scene) and records, for every direction p of the chosen steps:
///  - the step, the direction's index in it, how many entering springs it was solved with, the
///    CCD bound α on the step along p, the speed max_k ‖(Φp)_k‖ / h that Newton's stopping rule
///    compares with ε_d and the body of that surface point, ‖g‖ and E;
///  - friction's stick/slip changes up to the iterate and after the step along p is accepted,
///    and its sticking and sliding stencils at the iterate;
///  - E(q + s p) − E(q) for s = 1, 1.5, 2 and 3 where CCD admits the whole step s p (empty
///    from the first s it does not): where along p the energy is lowest;
///  - of the active contacts: how many, how many the step α p takes 0.35–0.65 of the way out of
///    d̂ ((d̂ − d₁) / (d̂ − d₀) in that range), how many it takes out of d̂; and for the contact
///    whose distance it changes most, that change / h, d₀ / d̂ and (d̂ − d₁) / (d̂ − d₀).
/// The probes leave the run unchanged: each is evaluated and the terms put back at the iterate.
/// `scripts/newton_trace.py` summarises the CSV by place from each step's end.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <stiffsoft/coupling/contact/squared_distance.hpp>
#include <stiffsoft/coupling/terms/barrier_term.hpp>
#include <stiffsoft/coupling/terms/friction_term.hpp>
#include <stiffsoft/scene/make_simulation.hpp>

#include "run_options.hpp"

using namespace stiffsoft;

namespace {

/// The multiples of p at which the energy is sampled.
constexpr std::array<double, 4> kLineSamples{1.0, 1.5, 2.0, 3.0};

/// One Newton direction's row.
struct Row {
  int step = 0, iteration = 0;
  std::size_t springs = 0;  ///< entering springs the direction was solved with
  int fastest_body = -1;    ///< the body of the surface point p moves most
  double alpha = 0, speed = 0, gradient_norm = 0, energy = 0;
  int flips_before = 0, flips_after = 0, sticking = 0, sliding = 0;
  std::array<double, kLineSamples.size()> line{NAN, NAN, NAN, NAN};  ///< E(q + s p) − E(q)
  int contacts = 0, halving = 0, leaving = 0;
  double gap_speed = 0, gap_start = NAN, gap_ratio = NAN;  ///< of the contact whose distance moves most
};

/// The iterate's term of type Term, or null when the scene has none (no friction with μ = 0).
template <class Term>
const Term* find_term(const NewtonIterate& it) {
  for (const EnergyTerm* t : it.terms)
    if (const auto* found = dynamic_cast<const Term*>(t)) return found;
  return nullptr;
}

/// E at q + s p for each line sample s, as long as CCD admits the whole step s p.
void sample_line(const NewtonIterate& it, const Eigen::MatrixX3d& dx, Row& row) {
  for (std::size_t i = 0; i < kLineSamples.size(); ++i) {
    const double s = kLineSamples[i];
    const Eigen::VectorXd dq = s * it.p;
    const Eigen::MatrixX3d dxs = s * dx;
    double bound = 1.0;
    for (const EnergyTerm* t : it.terms) bound = std::min(bound, t->max_step(it.c, dq, dxs));
    if (bound < 1.0) break;
    const Eigen::VectorXd q = it.c.q + dq;
    const Eigen::MatrixX3d x = it.model.surface(q);
    for (EnergyTerm* t : it.terms) t->update({q, x});
    double E = 0;
    for (const EnergyTerm* t : it.terms) E += t->value({q, x});
    row.line[i] = E - it.energy;
  }
  for (EnergyTerm* t : it.terms) t->update(it.c);  // as Newton left them
}

/// The active contacts along the step α p.
void follow_contacts(const BarrierTerm& barrier, const NewtonIterate& it, const Eigen::MatrixX3d& dx, double h,
                     Row& row) {
  const double dhat = barrier.dhat();
  for (const ContactConstraint& k : barrier.constraints()) {
    const contact::Vector12d x0 = gather(it.c.x, k.vertices);
    const contact::Vector12d x1 = x0 + it.alpha * gather(dx, k.vertices);
    const double d0 = std::sqrt(contact::stencil_squared_distance(k.stencil, x0));
    const double d1 = std::sqrt(contact::stencil_squared_distance(k.stencil, x1));
    const double ratio = (dhat - d1) / (dhat - d0);
    ++row.contacts;
    row.halving += ratio > 0.35 && ratio < 0.65;
    row.leaving += d1 >= dhat;
    if (std::abs(d1 - d0) / h > row.gap_speed) {
      row.gap_speed = std::abs(d1 - d0) / h;
      row.gap_start = d0 / dhat;
      row.gap_ratio = ratio;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"newton_trace: one CSV row per Newton direction of a run (docs/newton.md, session 36)"};
  tools::RunOptions options;
  std::string csv;
  options.add_to(app, "trace");
  app.add_option("--csv", csv, "the rows go here")->required();
  CLI11_PARSE(app, argc, argv);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(options.threads));

  try {
    SceneSimulation run = make_simulation(options.scene_file);
    Simulation& sim = run.simulation;
    tools::resume_run(run, options);
    std::ofstream out(csv);
    out.precision(17);
    if (!out) throw std::runtime_error(csv + ": cannot be written");
    out << "step,iteration,springs,alpha,speed,fastest_body,gradient_norm,energy,flips_before,flips_after,sticking,sliding";
    for (double s : kLineSamples) out << ",line_" << s;
    out << ",contacts,halving,leaving,gap_speed,gap_start,gap_ratio\n";
    const double h = sim.settings().h;
    std::vector<Row> rows;  // the current step's
    sim.observe_newton([&](const NewtonIterate& it) {
      Row row;
      row.step = sim.state().step + 1;
      row.iteration = it.iteration;
      row.springs = it.springs;
      row.alpha = it.alpha;
      const Eigen::MatrixX3d dx = it.model.surface_step(it.p);
      if (dx.rows()) {
        Eigen::Index fastest = 0;
        row.speed = dx.rowwise().norm().maxCoeff(&fastest) / h;
        row.fastest_body = it.model.mesh.vertex_body[std::size_t(fastest)];
      }
      row.gradient_norm = it.g.norm();
      row.energy = it.energy;
      if (const FrictionTerm* friction = find_term<FrictionTerm>(it)) {
        const FrictionTerm::StickSlip s = friction->stick_slip(it.c);
        row.flips_before = friction->stick_slip_flips();
        row.sticking = s.sticking;
        row.sliding = s.sliding;
      }
      if (it.alpha >= 1.0) sample_line(it, dx, row);
      if (const BarrierTerm* barrier = find_term<BarrierTerm>(it)) follow_contacts(*barrier, it, dx, h, row);
      rows.push_back(row);
    });
    for (int k = 0; k < options.steps; ++k) {
      rows.clear();
      const StepStats stats = sim.step();
      // A direction's changes end where the next direction's begin; the last one's with the step.
      for (std::size_t i = 0; i < rows.size(); ++i)
        rows[i].flips_after = i + 1 < rows.size() ? rows[i + 1].flips_before : stats.stick_slip_flips;
      for (const Row& r : rows) {
        out << r.step << ',' << r.iteration << ',' << r.springs << ',' << r.alpha << ',' << r.speed << ','
            << r.fastest_body << ',' << r.gradient_norm << ',' << r.energy << ',' << r.flips_before << ',' << r.flips_after << ',' << r.sticking << ',' << r.sliding;
        for (double v : r.line) {
          out << ',';
          if (!std::isnan(v)) out << v;
        }
        out << ',' << r.contacts << ',' << r.halving << ',' << r.leaving << ',' << r.gap_speed << ',' << r.gap_start
            << ',' << r.gap_ratio << '\n';
      }
      spdlog::info("step {}: {} iterations{}", stats.step, stats.newton.iterations,
                   stats.newton.converged ? "" : " (not converged)");
    }
    return 0;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
