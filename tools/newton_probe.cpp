/// @file newton_probe: the whole system's derivatives at the states of a real run, against
/// finite differences (issue 17's diagnosis). It continues a run from its checkpoint (or starts
/// the scene) and, at every Newton direction of the chosen steps, compares
///  - the gradient with central differences of the incremental potential E, along the
///    direction p and along a random direction, for E and for each term;
///  - the matrix p was solved with, H p, with central differences of the gradient along p; and
///    the curvature pᵀ H p with the exact curvature pᵀ ∇²E p, for E and for each term (each
///    term's own projected Hessian): the ratio says how much the PSD projection (and friction's
///    revision) changes Newton's model along the direction it takes;
///  - the energy decrease of the admissible step α p (α the CCD bound) with the quadratic
///    model's, ρ = ΔE / (α gᵀp + ½ α² pᵀHp): near 1 where the model holds over the step;
///  - the gradient at the step's end with the model's, ‖g(q + αp) − g − αHp‖ / ‖g‖, in all, per
///    term and for the barrier stencils that entered d̂ during the step, and the slope of E
///    along p there (0 at the line's minimum);
///  - each term's share of the slope of E along p at the step's end, against the model's;
///  - by barrier stencil kind, the share of the curvature along p that the projection adds.
/// Every difference is taken at three step lengths (surface displacements of 1e-4, 1e-5 and
/// 1e-6 d̂) and the smallest error reported. The probes leave the run's iterates unchanged:
/// each Newton iteration continues from its own state. `newton_probe --help` lists the options.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <stiffsoft/coupling/contact/barrier_potential.hpp>
#include <stiffsoft/coupling/model/stencil_jacobian.hpp>
#include <stiffsoft/coupling/terms/barrier_term.hpp>
#include <stiffsoft/scene/make_simulation.hpp>

#include "run_options.hpp"

using namespace stiffsoft;

namespace {

/// Every term's value and gradient at one configuration.
struct Sample {
  std::vector<double> value;
  std::vector<Eigen::VectorXd> gradient;
};

/// The terms updated at q and evaluated there, term by term.
Sample sample(const NewtonIterate& it, const Eigen::VectorXd& q) {
  const Eigen::MatrixX3d x = it.model.surface(q);
  const Configuration c{q, x};
  Sample s;
  for (EnergyTerm* t : it.terms) t->update(c);
  for (const EnergyTerm* t : it.terms) {
    s.value.push_back(t->value(c));
    s.gradient.push_back(Eigen::VectorXd::Zero(q.size()));
    t->add_gradient(c, s.gradient.back());
  }
  return s;
}

/// Σ of the terms' values.
double sum(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

/// Σ of the terms' gradients.
Eigen::VectorXd sum(const std::vector<Eigen::VectorXd>& v) {
  Eigen::VectorXd s = v.front();
  for (std::size_t k = 1; k < v.size(); ++k) s += v[k];
  return s;
}

/// |a − b| / max(|a|, |b|), 0 when both are 0.
double relative(double a, double b) {
  const double scale = std::max(std::abs(a), std::abs(b));
  return scale > 0 ? std::abs(a - b) / scale : 0.0;
}

/// Central differences along v at the three step lengths: per length, the samples at q ± ε v.
struct Differences {
  std::vector<double> eps;
  std::vector<Sample> plus, minus;
};

/// The samples of the terms at q ± ε v for the three step lengths.
Differences differences(const NewtonIterate& it, const Eigen::VectorXd& v, double dhat) {
  const Eigen::MatrixX3d dx = it.model.surface_step(v);
  const double reach = dx.rows() ? dx.rowwise().norm().maxCoeff() : 0.0;  // surface displacement per unit of v
  Differences d;
  for (double fraction : {1e-4, 1e-5, 1e-6}) {
    const double eps = fraction * dhat / std::max(reach, 1e-300);
    d.eps.push_back(eps);
    d.plus.push_back(sample(it, it.c.q + eps * v));
    d.minus.push_back(sample(it, it.c.q - eps * v));
  }
  return d;
}

/// The smallest error over the step lengths of the directional derivative gᵀv (term `t`, or
/// all terms with t < 0) against the differences of the value, relative to the larger of the
/// two for the sum and to Σ_t |g_tᵀv| for a term (a term that hardly changes along v is
/// measured on the scale of those that do, not on its own round-off).
double gradient_error(const Differences& d, const Sample& at, const Eigen::VectorXd& v, int t) {
  const double exact = t < 0 ? sum(at.gradient).dot(v) : at.gradient[t].dot(v);
  double scale = 0;
  for (const Eigen::VectorXd& g : at.gradient) scale += std::abs(g.dot(v));
  double best = 1e300;
  for (std::size_t k = 0; k < d.eps.size(); ++k) {
    const double plus = t < 0 ? sum(d.plus[k].value) : d.plus[k].value[t];
    const double minus = t < 0 ? sum(d.minus[k].value) : d.minus[k].value[t];
    const double fd = (plus - minus) / (2 * d.eps[k]);
    best = std::min(best, t < 0 ? relative(exact, fd) : std::abs(exact - fd) / std::max(scale, 1e-300));
  }
  return best;
}

/// ∇²E v (term t, or all with t < 0) by differences of the gradient at the step length whose
/// result agrees best with the next shorter one (the last pair's shorter one).
Eigen::VectorXd hessian_times(const Differences& d, int t) {
  std::vector<Eigen::VectorXd> Hv;
  for (std::size_t k = 0; k < d.eps.size(); ++k) {
    const Eigen::VectorXd plus = t < 0 ? sum(d.plus[k].gradient) : d.plus[k].gradient[t];
    const Eigen::VectorXd minus = t < 0 ? sum(d.minus[k].gradient) : d.minus[k].gradient[t];
    Hv.push_back((plus - minus) / (2 * d.eps[k]));
  }
  std::size_t best = 0;
  double best_change = 1e300;
  for (std::size_t k = 0; k + 1 < Hv.size(); ++k) {
    const double change = (Hv[k] - Hv[k + 1]).norm() / std::max(Hv[k + 1].norm(), 1e-300);
    if (change < best_change) best_change = change, best = k + 1;
  }
  return Hv[best];
}

/// Stencil kinds of the barrier's breakdown: its primitive pair, mollified edge pairs apart.
constexpr const char* kKinds[] = {"vertex_vertex", "edge_vertex", "edge_edge", "face_vertex", "edge_edge_mollified"};
constexpr int kKindCount = 5;

/// One probed direction.
struct Row {
  int step, iteration, contacts;
  double alpha, speed, gradient_p, gradient_random, hessian_p, curvature_ratio, rho;
  /// ‖g(q + αp) − g − α H p‖ / ‖g‖: how far the gradient at the step's end is from the
  /// quadratic model's (0 for a quadratic E), the nonlinearity Newton meets over the step.
  double gradient_model;
  /// φ′(α) / φ′(0) for φ(t) = E(q + t p): 1 where E still falls as fast as at q, 0 at the
  /// line's minimum, negative past it.
  double slope_ratio;
  /// ‖gradient at the step's end of the barrier stencils that were not active at q‖ / ‖g‖:
  /// the part of the model's error from contacts that entered d̂ during the step.
  double new_contacts;
  std::vector<double> term_gradient, term_curvature_ratio;
  /// Per term: ‖g_t(q + αp) − g_t − α H_t p‖ / ‖g‖ (H_t the term's own Hessian).
  std::vector<double> term_gradient_model;
  /// Per term: (g_t(q + αp) − g_t − α H_t p)ᵀ p / |gᵀp|, the term's share of where the slope of
  /// E along p at the step's end departs from the model's (the model's slope is 0 there for a
  /// full step): negative where the term falls further than its model, so that the model was too
  /// stiff along p for it. The last entry is α (Σ_t H_t − H) p ᵀ p / |gᵀp|: what the solved matrix
  /// takes away from or adds to the terms' own Hessians (the released contacts' reduced
  /// Hessian, friction's revision).
  std::vector<double> term_slope_model;
  /// Per barrier stencil kind: κ Σ dxᵀ (Π₊∇²P − ∇²P) dx over its stencils, the curvature the
  /// projection adds along p (J m⁻²·m², i.e. J), as a share of the barrier's whole addition.
  std::array<double, kKindCount> projection_share{};
};

/// The barrier's curvature along dx that the PSD projection adds, by stencil kind (J).
std::array<double, kKindCount> projection_excess(const BarrierTerm& barrier, const Configuration& c,
                                                 const Eigen::MatrixX3d& dx) {
  std::array<double, kKindCount> excess{};
  for (const ContactConstraint& k : barrier.constraints()) {
    const contact::Vector12d x = gather(c.x, k.vertices), v = gather(dx, k.vertices);
    const contact::Matrix12d exact = contact::barrier_potential_hessian(k.stencil, x, barrier.dhat(), false);
    const contact::Matrix12d projected = contact::barrier_potential_hessian(k.stencil, x, barrier.dhat(), true);
    const int kind = contact::is_mollified(k.stencil) && contact::mollifier_active(k.stencil, x) ? 4 : int(k.stencil.kind);
    excess[kind] += barrier.kappa() * k.weight * v.dot((projected - exact) * v);
  }
  return excess;
}

/// Every comparison at one Newton direction; leaves the terms updated at the iterate.
Row probe(const NewtonIterate& it, double dhat, double h, std::mt19937& rng) {
  const Eigen::VectorXd& q = it.c.q;
  const Eigen::VectorXd& p = it.p;
  const int nt = int(it.terms.size());
  const Sample at = sample(it, q);
  const BarrierTerm* barrier = nullptr;
  for (const EnergyTerm* t : it.terms)
    if (const auto* b = dynamic_cast<const BarrierTerm*>(t)) barrier = b;
  std::set<std::array<int, 4>> active;  // the stencils active at q, by their vertices
  if (barrier)
    for (const ContactConstraint& k : barrier->constraints()) active.insert(k.vertices);
  Row row{};
  row.iteration = it.iteration;
  const Eigen::MatrixX3d dx = it.model.surface_step(p);
  row.speed = (dx.rows() ? dx.rowwise().norm().maxCoeff() : 0.0) / h;
  row.alpha = it.alpha;
  if (barrier) {  // its constraints are those at q until the next sample()
    const auto excess = projection_excess(*barrier, it.c, dx);
    double total = 0;
    for (double e : excess) total += e;
    for (int k = 0; k < kKindCount; ++k) row.projection_share[k] = total > 0 ? excess[k] / total : 0.0;
  }

  std::normal_distribution<double> normal;
  Eigen::VectorXd r(q.size());
  for (Eigen::Index i = 0; i < r.size(); ++i) r[i] = normal(rng);
  r = r.cwiseProduct(p.cwiseAbs().cwiseMax(1e-12 * p.cwiseAbs().maxCoeff()));  // each DOF on p's scale

  const Differences along_p = differences(it, p, dhat);
  const Differences along_r = differences(it, r, dhat);
  row.gradient_p = gradient_error(along_p, at, p, -1);
  row.gradient_random = gradient_error(along_r, at, r, -1);
  for (int t = 0; t < nt; ++t)
    row.term_gradient.push_back(std::max(gradient_error(along_p, at, p, t), gradient_error(along_r, at, r, t)));

  const Eigen::VectorXd Hp = it.H.multiply(p);
  const Eigen::VectorXd exact_Hp = hessian_times(along_p, -1);
  row.hessian_p = (Hp - exact_Hp).norm() / std::max(exact_Hp.norm(), 1e-300);
  row.curvature_ratio = p.dot(Hp) / p.dot(exact_Hp);
  // Each term's own Hessian along p, with the terms updated at q again (the differences left
  // them elsewhere).
  for (EnergyTerm* t : it.terms) t->update(it.c);
  std::vector<Eigen::VectorXd> term_Hp;
  BlockHessian H_t(it.model.blocks);
  for (int t = 0; t < nt; ++t) {
    H_t.clear();
    it.terms[t]->add_hessian(it.c, H_t);
    term_Hp.push_back(H_t.multiply(p));
    const double exact = p.dot(hessian_times(along_p, t));
    const double model = p.dot(term_Hp.back());
    row.term_curvature_ratio.push_back(exact != 0 ? model / exact : (model == 0 ? 1.0 : INFINITY));
  }
  const Eigen::VectorXd q_end = q + it.alpha * p;
  const Sample end = sample(it, q_end);
  const double g_norm = std::max(it.g.norm(), 1e-300);
  row.gradient_model = (sum(end.gradient) - sum(at.gradient) - it.alpha * Hp).norm() / g_norm;
  row.slope_ratio = sum(end.gradient).dot(p) / it.g.dot(p);
  if (barrier) {
    Eigen::VectorXd g_new = Eigen::VectorXd::Zero(q.size());
    const Eigen::MatrixX3d x_end = it.model.surface(q_end);
    for (const ContactConstraint& k : barrier->constraints())  // updated at the step's end by sample()
      if (!active.count(k.vertices))
        StencilJacobian(it.model, k.vertices)
            .scatter_gradient(barrier->kappa() * k.weight *
                                  contact::barrier_potential_gradient(k.stencil, gather(x_end, k.vertices), barrier->dhat()),
                              g_new);
    row.new_contacts = g_new.norm() / g_norm;
  }
  const double slope_scale = std::max(std::abs(it.g.dot(p)), 1e-300);
  Eigen::VectorXd sum_Hp = Eigen::VectorXd::Zero(q.size());
  for (int t = 0; t < nt; ++t) {
    const Eigen::VectorXd miss = end.gradient[t] - at.gradient[t] - it.alpha * term_Hp[t];
    row.term_gradient_model.push_back(miss.norm() / g_norm);
    row.term_slope_model.push_back(miss.dot(p) / slope_scale);
    sum_Hp += term_Hp[t];
  }
  row.term_slope_model.push_back(it.alpha * (sum_Hp - Hp).dot(p) / slope_scale);

  const double predicted = it.alpha * it.g.dot(p) + 0.5 * it.alpha * it.alpha * p.dot(Hp);
  const double actual = sum(end.value) - sum(at.value);
  row.rho = predicted != 0 ? actual / predicted : NAN;
  for (EnergyTerm* t : it.terms) t->update(it.c);  // as Newton left them
  return row;
}

/// The median (the upper one of an even count), NaN when empty.
double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"newton_probe: gradient, Hessian and model checks of every Newton direction at a run's states"};
  tools::RunOptions options;
  std::string csv;
  unsigned seed = 1;
  options.add_to(app, "probe");
  app.add_option("--seed", seed, "seed of the random directions");
  app.add_option("--csv", csv, "write one row per probed direction here");
  CLI11_PARSE(app, argc, argv);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(options.threads));

  try {
    SceneSimulation run = make_simulation(options.scene_file);
    Simulation& sim = run.simulation;
    tools::resume_run(run, options);
    const double dhat = sim.settings().dhat, h = sim.settings().h;
    std::mt19937 rng(seed);
    std::vector<Row> rows;
    std::vector<std::string> names;
    int step = sim.state().step + 1;
    const double tolerance = sim.settings().tolerance;
    std::size_t skipped = 0;
    sim.observe_newton([&](const NewtonIterate& it) {
      // A direction far below the tolerance (a free fall that the initial guess solved) is
      // round-off: nothing to compare.
      const Eigen::MatrixX3d dx = it.model.surface_step(it.p);
      if ((dx.rows() ? dx.rowwise().norm().maxCoeff() : 0.0) / h < 1e-6 * tolerance) {
        ++skipped;
        return;
      }
      if (names.empty())
        for (const EnergyTerm* t : it.terms) names.push_back(t->name());
      Row row = probe(it, dhat, h, rng);
      row.step = step;
      rows.push_back(row);
    });
    std::ofstream out;
    if (!csv.empty()) out.open(csv);
    for (int k = 0; k < options.steps; ++k, ++step) {
      const std::size_t first = rows.size();
      const StepStats stats = sim.step();
      for (std::size_t i = first; i < rows.size(); ++i) rows[i].contacts = stats.contacts;
      spdlog::info("step {}: {} iterations{}", stats.step, stats.newton.iterations,
                   stats.newton.converged ? "" : " (not converged)");
    }
    if (out) {
      out << "step,iteration,contacts,alpha,speed,gradient_p,gradient_random,hessian_p,curvature_ratio,rho,gradient_model,slope_ratio,new_contacts";
      for (const std::string& n : names) out << ",gradient_" << n;
      for (const std::string& n : names) out << ",curvature_ratio_" << n;
      for (const std::string& n : names) out << ",gradient_model_" << n;
      for (const std::string& n : names) out << ",slope_model_" << n;
      out << ",slope_model_revision";
      for (const char* kind : kKinds) out << ",projection_share_" << kind;
      out << "\n";
      for (const Row& r : rows) {
        out << r.step << ',' << r.iteration << ',' << r.contacts << ',' << r.alpha << ',' << r.speed << ','
            << r.gradient_p << ',' << r.gradient_random << ',' << r.hessian_p << ',' << r.curvature_ratio << ','
            << r.rho << ',' << r.gradient_model << ',' << r.slope_ratio << ',' << r.new_contacts;
        for (double v : r.term_gradient) out << ',' << v;
        for (double v : r.term_curvature_ratio) out << ',' << v;
        for (double v : r.term_gradient_model) out << ',' << v;
        for (double v : r.term_slope_model) out << ',' << v;
        for (double v : r.projection_share) out << ',' << v;
        out << "\n";
      }
    }
    const auto column = [&](auto get) {
      std::vector<double> v;
      for (const Row& r : rows) v.push_back(get(r));
      return v;
    };
    const auto report = [&](const std::string& what, const std::vector<double>& v) {
      std::cout << "| " << what << " | " << median(v) << " | " << *std::min_element(v.begin(), v.end()) << " | "
                << *std::max_element(v.begin(), v.end()) << " |\n";
    };
    if (rows.empty()) {
      std::cout << "no Newton direction was probed\n";
      return 0;
    }
    std::cout << skipped << " directions slower than 1e-6 ε_d not probed\n";
    std::cout << "| " << rows.size() << " directions | median | min | max |\n|---|---|---|---|\n";
    report("gradient error along p", column([](const Row& r) { return r.gradient_p; }));
    report("gradient error, random direction", column([](const Row& r) { return r.gradient_random; }));
    report("‖H p − ∇²E p‖ / ‖∇²E p‖", column([](const Row& r) { return r.hessian_p; }));
    report("pᵀHp / pᵀ∇²E p", column([](const Row& r) { return r.curvature_ratio; }));
    report("ρ = ΔE / model", column([](const Row& r) { return r.rho; }));
    report("‖g(q + αp) − g − αHp‖ / ‖g‖", column([](const Row& r) { return r.gradient_model; }));
    report("φ′(α) / φ′(0) along p", column([](const Row& r) { return r.slope_ratio; }));
    report("‖g of contacts new at the step's end‖ / ‖g‖", column([](const Row& r) { return r.new_contacts; }));
    for (std::size_t t = 0; t < names.size(); ++t) {
      report("gradient error, " + names[t], column([&](const Row& r) { return r.term_gradient[t]; }));
      report("curvature ratio, " + names[t], column([&](const Row& r) { return r.term_curvature_ratio[t]; }));
      report("gradient model error, " + names[t], column([&](const Row& r) { return r.term_gradient_model[t]; }));
      report("slope model error, " + names[t], column([&](const Row& r) { return r.term_slope_model[t]; }));
    }
    report("slope model error, friction's revision", column([&](const Row& r) { return r.term_slope_model.back(); }));
    for (int k = 0; k < kKindCount; ++k)
      report(std::string("share of the barrier's projection, ") + kKinds[k],
             column([&](const Row& r) { return r.projection_share[k]; }));
    return 0;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
