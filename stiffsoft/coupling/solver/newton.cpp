#include <stiffsoft/coupling/solver/newton.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include <stiffsoft/coupling/linear_solver/forcing_term.hpp>
#include <stiffsoft/coupling/solver/entering_springs.hpp>

namespace stiffsoft {

namespace {

/// A geodesic trial whose cut chord stretches turning bodies by at least this fraction of the
/// decrease the trial promises goes to the path's own points instead (docs/newton.md, session
/// 41: 0.03, 0.1, 0.3 and 1 measured on medium and full at h = 1/100 and 1/240).
constexpr double kChordStretch = 0.1;

double total_energy(const std::vector<EnergyTerm*>& terms, const Configuration& c) {
  double e = 0;
  for (const EnergyTerm* t : terms) e += t->value(c);
  return e;
}

void update_all(const std::vector<EnergyTerm*>& terms, const Configuration& c) {
  for (EnergyTerm* t : terms) t->update(c);
}

/// The largest move of a surface point in the surface step dx (m); 0 without surface points.
double largest_move(const Eigen::MatrixX3d& dx) { return dx.rows() ? dx.rowwise().norm().maxCoeff() : 0.0; }

/// Whether CCD allows the whole move dq (surface step dx) from c, with the terms updated at c
/// (the barrier then tests a small move on its kept candidates alone: keeps_clear).
bool full_step_allowed(const std::vector<EnergyTerm*>& terms, const Configuration& c, const Eigen::VectorXd& dq,
                       const Eigen::MatrixX3d& dx) {
  for (const EnergyTerm* t : terms)
    if (t->max_step(c, dq, dx) < 1) return false;
  return true;
}

/// E at q + dq; leaves the terms updated there.
double full_step_energy(const Model& model, const std::vector<EnergyTerm*>& terms, const Configuration& c,
                        const Eigen::VectorXd& dq) {
  const Eigen::VectorXd q = c.q + dq;
  const Eigen::MatrixX3d x = model.surface(q);
  update_all(terms, {q, x});
  return total_energy(terms, {q, x});
}

/// gᵀ dq over each island's DOF blocks (islands numbered), summed block by block in order.
std::vector<double> island_slopes(const Model& model, const BlockIslands& islands, const Eigen::VectorXd& g,
                                  const Eigen::VectorXd& dq) {
  std::vector<double> slope(std::size_t(islands.count()), 0.0);
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const DofBlock& block = model.blocks[b];
    slope[std::size_t(islands.island(int(b)))] += g.segment(block.offset, block.size).dot(dq.segment(block.offset, block.size));
  }
  return slope;
}

/// The Newton direction p = −H⁻¹g; if the projected Hessian is numerically singular, shifts
/// its diagonal until the factorisation succeeds. The solver reads H's blocks in place, or,
/// with joints' eliminated equalities, the reduced compressed matrix.
/// `analysed` holds the pattern_version() the solver last analysed (empty: none yet).
bool newton_direction(const BlockHessian& H, const Eigen::VectorXd& g, LinearSolver& solver,
                      std::optional<std::uint64_t>& analysed, PhaseTimes& times, const ReducedBasis* basis,
                      Eigen::VectorXd& p) {
  ScopedTimer timer(times.solve);
  const BlockUpper blocks = H.upper_blocks();
  Eigen::SparseMatrix<double> reduced;
  if (basis) reduced = basis->reduce_upper(blocks.compressed());
  const Eigen::VectorXd b = basis ? Eigen::VectorXd(-basis->reduce(g)) : Eigen::VectorXd(-g);
  if (analysed != H.pattern_version()) {
    if (basis)
      solver.analyze_pattern(reduced);
    else
      solver.analyze_blocks(blocks);
    analysed = H.pattern_version();
  }
  const Eigen::VectorXd diagonal = basis ? Eigen::VectorXd(reduced.diagonal()) : blocks.diagonal();
  const double scale = diagonal.cwiseAbs().maxCoeff();
  double shift = 0;
  for (int attempt = 0; attempt < 8; ++attempt) {
    if (basis)
      for (int i = 0; i < reduced.rows(); ++i) reduced.coeffRef(i, i) = diagonal[i] + shift;
    if (basis ? solver.factorize(reduced) : solver.factorize_blocks(blocks, shift)) {
      p = solver.solve(b);
      if (basis && p.allFinite()) p = basis->expand(p);
      if (p.allFinite()) return true;
    }
    shift = shift == 0 ? 1e-10 * scale : 10 * shift;
  }
  return false;
}

}  // namespace

void accumulate(NewtonReport& total, const NewtonReport& next) {
  total.converged = next.converged;
  total.iterations += next.iterations;
  total.line_search_steps += next.line_search_steps;
  total.line_search_halvings += next.line_search_halvings;
  total.smallest_ccd_step = std::min(total.smallest_ccd_step, next.smallest_ccd_step);
  total.ccd_limited_iterations += next.ccd_limited_iterations;
  total.revised_directions += next.revised_directions;
  total.entering_directions += next.entering_directions;
  total.energy = next.energy;
  total.last_step_speed = next.last_step_speed;
  total.linear_iterations += next.linear_iterations;
  total.linear_fallbacks += next.linear_fallbacks;
  if (total.linear_failure.empty()) total.linear_failure = next.linear_failure;
  total.failure = next.failure;
}

std::vector<double> island_multiples(const std::vector<double>& bound, double alpha, const std::vector<double>& slope) {
  std::vector<double> multiple(bound.size());
  double descent = 0;
  for (std::size_t i = 0; i < bound.size(); ++i) {
    multiple[i] = std::min(bound[i], alpha);
    descent += multiple[i] * slope[i];
  }
  if (!(descent < 0) && !multiple.empty())
    std::fill(multiple.begin(), multiple.end(), *std::min_element(multiple.begin(), multiple.end()));
  return multiple;
}

NewtonReport newton_minimize(const Model& model, const std::vector<EnergyTerm*>& terms,
                             Eigen::VectorXd& q, LinearSolver& solver, const NewtonSettings& settings,
                             PhaseTimes& times, const ReducedBasis* basis, BlockHessian* hessian) {
  NewtonReport report;
  Eigen::MatrixX3d x = model.surface(q);
  update_all(terms, {q, x});
  double E = total_energy(terms, {q, x});
  std::optional<std::uint64_t> analysed;
  std::optional<BlockHessian> own_hessian;
  // Reused: the same pattern is assembled without allocating.
  BlockHessian& H = hessian ? *hessian : own_hessian.emplace(model.blocks);
  Eigen::VectorXd g(q.size()), p(q.size()), q_trial(q.size());
  double eta = 0, g_norm_previous = 0;  // Eisenstat–Walker state
  std::vector<char> held(model.blocks.size(), 0);
  for (int b : settings.held_blocks) held[b] = 1;
  const bool holds = !settings.held_blocks.empty();
  // Zeroes v on the held blocks.
  const auto hold = [&](Eigen::VectorXd& v) {
    for (int b : settings.held_blocks) v.segment(model.blocks[b].offset, model.blocks[b].size).setZero();
  };
  if (basis && solver.is_iterative())
    throw std::invalid_argument("newton_minimize: the " + solver.name() +
                                " linear solver is iterative, which joints' eliminated equalities do not support; "
                                "use cholmod");
  // Direct backends ignore the block sizes and η; `auto` may turn iterative at any analysis.
  if (!basis) {
    std::vector<int> sizes;
    for (const DofBlock& b : model.blocks) sizes.push_back(b.size);
    solver.set_block_sizes(sizes);
  }

  std::string gap_note;  // why a slow last direction did not stop Newton, for the failure message
  for (; report.iterations < settings.max_iterations; ++report.iterations) {
    const Configuration c{q, x};
    g.setZero();
    {
      ScopedTimer timer(times.assembly);
      for (const EnergyTerm* t : terms) t->add_gradient(c, g);
    }
    if (holds) hold(g);
    const double g_norm = g.norm();
    eta = forcing_term(g_norm, g_norm_previous, eta, settings.forcing);
    g_norm_previous = g_norm;
    solver.set_relative_tolerance(eta);
    H.clear();
    {
      ScopedTimer timer(times.assembly);
      for (const EnergyTerm* t : terms) t->add_hessian(c, H);
      if (holds) H.decouple(held);
    }
    const bool solved = newton_direction(H, g, solver, analysed, times, basis, p);
    if (holds) hold(p);  // exact zeros, whatever the solver (a multigrid cycle may mix blocks)
    const LinearSolveReport& linear = solver.last_report();
    report.linear_iterations += linear.iterations;
    report.linear_fallbacks += linear.fallback_used;
    if ((linear.fallback_used || !solved) && report.linear_failure.empty())
      report.linear_failure = "iteration " + std::to_string(report.iterations + 1) + ": " +
                              (linear.fallback_used ? linear.primary_failure + ", solved by the fallback"
                                                    : std::string(to_string(linear.status)) + " " + linear.reason);
    if (!solved) {
      report.failure = "the linear solve failed even with a regularised Hessian (" + report.linear_failure + ")";
      break;
    }
    Eigen::MatrixX3d dx = model.surface_step(p);
    // A full step the comparison of two full steps below took, and its E: a trial there has it.
    Eigen::VectorXd q_full;
    double E_full = 0;
    bool revised = false;
    {
      ScopedTimer timer(times.assembly);
      for (const EnergyTerm* t : terms) revised = t->revise_hessian(c, p, dx, H) || revised;
      if (revised && holds) H.decouple(held);
    }
    if (revised) {
      // Same sparsity (the revision only changes existing stencils' blocks): no new analysis.
      // Should the revised solve fail, the first direction stands.
      Eigen::VectorXd p_revised(p.size());
      const bool resolved = newton_direction(H, g, solver, analysed, times, basis, p_revised);
      report.linear_iterations += solver.last_report().iterations;
      if (resolved) {
        if (holds) hold(p_revised);
        // A revision models where a long step goes. Where the unrevised direction already meets
        // the speed rule, its model is right to second order, and a revision can overshoot (a
        // released contact that carries load: a body resting on a face rocked from step to step,
        // docs/newton.md, session 46): there the unrevised direction stands where its full step
        // ends at a lower E than the revised one's.
        Eigen::MatrixX3d dx_revised = model.surface_step(p_revised);
        bool unrevised_lower = false;
        if (largest_move(dx) < settings.tolerance * settings.h) {  // dx is still the unrevised step
          // Both moves bounded first, while the terms are at c; a move CCD cuts counts as +∞.
          const bool revised_allowed = full_step_allowed(terms, c, p_revised, dx_revised);
          const bool unrevised_allowed = full_step_allowed(terms, c, p, dx);
          constexpr double kCut = std::numeric_limits<double>::infinity();
          const double E_revised = revised_allowed ? full_step_energy(model, terms, c, p_revised) : kCut;
          const double E_unrevised = unrevised_allowed ? full_step_energy(model, terms, c, p) : kCut;
          unrevised_lower = E_unrevised < E_revised;
          if (unrevised_lower || revised_allowed) {
            q_full = q + (unrevised_lower ? p : p_revised);
            E_full = unrevised_lower ? E_unrevised : E_revised;
          }
          update_all(terms, c);
        }
        if (!unrevised_lower) {
          p.swap(p_revised);
          dx.swap(dx_revised);
          ++report.revised_directions;
        }
      }
    }
    // The largest fraction of a move dq from q that CCD finds free of intersections, per
    // island of the blocks the terms couple on that move (one island without
    // island_line_search, or when a term couples everything).
    struct MoveBounds {
      BlockIslands islands;
      std::vector<double> bound;  // per island
      double smallest = 1.0;
    };
    const bool by_island = settings.island_line_search && !basis;
    const auto move_bounds = [&](const Eigen::VectorXd& dq, const Eigen::MatrixX3d& dx_dq) {
      MoveBounds m{BlockIslands(int(model.blocks.size())), {}, 1.0};
      if (by_island) {
        for (const EnergyTerm* t : terms) t->join_coupled_blocks(c, dx_dq, m.islands);
        m.islands.number();
        m.bound.assign(std::size_t(m.islands.count()), 1.0);
        // On the broad phases the joins built.
        for (const EnergyTerm* t : terms) t->max_step_per_island(c, dq, dx_dq, m.islands, m.bound);
      } else {
        m.islands.join_all();
        m.islands.number();
        m.bound.assign(1, 1.0);
        for (const EnergyTerm* t : terms) m.bound[0] = std::min(m.bound[0], t->max_step(c, dq, dx_dq));
      }
      m.smallest = *std::min_element(m.bound.begin(), m.bound.end());
      return m;
    };
    // Trials are q + α p, or the geodesic path's q(α), for α = 1, ½, ¼, … A straight trial
    // moves each island by its own multiple of p, starting at its CCD bound; a geodesic trial
    // moves each island along its part of the chord from q to q(α), cut to that island's CCD
    // bound βᵢ of the chord (the segment linear CCD checks exactly). Part of a chord between two
    // turns is no turn: where that stretches the cut islands' turning bodies by at least
    // kChordStretch of what the trial promises, each island goes instead to the path's own
    // point q(α βᵢ), whose chord is bounded again. Once a geodesic trial does not lower E (or CCD
    // lets some island's chord not move at all), the search goes on along the straight line
    // from the same α: never worse than the line where the energy is not the orthogonality's (a
    // turn far from a rotation, a test energy).
    std::optional<TrialPath> path;
    std::optional<MoveBounds> line;  // p's bounds, once needed
    Eigen::VectorXd chord;
    std::optional<MoveBounds> chord_bounds;
    const auto bound_chord = [&](double a) {  // leaves q(a) in q_trial
      path->point(a, q_trial);
      chord = q_trial - q;
      chord_bounds = move_bounds(chord, model.surface_step(chord));
      return chord_bounds->smallest;
    };
    // The path along p and the CCD bound of its first trial (α = 1).
    const auto first_bound = [&] {
      path.emplace(model, q, p, settings.geodesic_line_search && !basis, std::abs(g.dot(p)));
      line.reset();
      chord_bounds.reset();
      if (!path->straight()) return bound_chord(1.0);
      line = move_bounds(p, dx);
      return line->smallest;
    };
    double bound = first_bound();
    // CCD cut the first trial: solve again with springs on the pairs it found entering d̂.
    std::size_t springs_used = 0;
    if (settings.entering_springs && bound < 1) {
      std::vector<EnteringPair> entering;
      for (const EnergyTerm* t : terms) t->entering_pairs(c, entering);
      EnteringSprings springs(model, std::move(entering));
      const EnteringSprings::Solve solve_h = [&](const Eigen::VectorXd& g_springs, Eigen::VectorXd& out) {
        if (holds) H.decouple(held);
        const bool ok = newton_direction(H, g_springs, solver, analysed, times, basis, out);
        report.linear_iterations += solver.last_report().iterations;
        if (ok && holds) hold(out);
        return ok;
      };
      if (springs.size() > 0 && springs.solve(H, g, solve_h, p)) {
        dx = model.surface_step(p);
        bound = first_bound();
        ++report.entering_directions;
        springs_used = springs.size();
      }
    }
    report.last_step_speed = largest_move(dx) / settings.h;
    // Converged when the direction moves no surface point faster than ε_d and changes no active
    // contact's gap by more than gap_tolerance of it: a contact pressed deep into the barrier
    // moves out by only about its own gap per iteration, a move the speed rule alone takes for
    // convergence. The last (small) step is still taken, as its first trial (CCD-bounded, so
    // intersection-free) where that does not raise E: skipping it would freeze a body whose
    // per-step velocity change is below ε_d, e.g. a block starting to slide, and halving it spent
    // several trials on energy changes at round-off (docs/newton.md, session 40). A first trial
    // that raises E is neither taken nor halved: Newton stops where it is. Taken, such a step
    // left its error to the next time step, and a body resting on a face rocked for good
    // (session 46).
    // With stick_tolerance set, it must also move no sticking friction stencil by more than that
    // fraction of ε_v h: in the stick zone friction's stiffness makes every direction short, so
    // a block that should break loose from it would otherwise stop there.
    const bool slow = report.last_step_speed < settings.tolerance;
    double gap_change = 0, stick_step = 0;
    if (slow)
      for (const EnergyTerm* t : terms) {
        gap_change = std::max(gap_change, t->relative_gap_change(c, dx));
        if (std::isfinite(settings.stick_tolerance)) stick_step = std::max(stick_step, t->stick_zone_step(c, dx));
      }
    const bool small_step = slow && gap_change <= settings.gap_tolerance && stick_step <= settings.stick_tolerance;
    gap_note.clear();
    if (slow && gap_change > settings.gap_tolerance)
      gap_note = " (the last direction was below the speed tolerance but changed a contact's gap by " +
                 std::to_string(int(std::lround(100 * gap_change))) + " %, above solver.gap_tolerance)";
    else if (slow && !small_step)
      gap_note = " (the last direction was below the speed tolerance but moved a sticking friction contact by " +
                 std::to_string(int(std::lround(100 * stick_step))) + " % of ε_v h, above " +
                 std::to_string(int(std::lround(100 * settings.stick_tolerance))) + " %)";
    const double decrease = std::abs(g.dot(p));  // what the direction's first order promises at α = 1
    bool straight = path->straight();
    std::vector<double> scale;       // straight trials: each island of `line` moves by scale[i] p
    double alpha = 1.0;              // geodesic: the path's α; straight: the largest scale
    const auto go_straight = [&](double a) {  // the straight line from α = a
      if (!line) line = move_bounds(p, dx);
      straight = true;
      scale = island_multiples(line->bound, a, island_slopes(model, line->islands, g, p));
      alpha = *std::max_element(scale.begin(), scale.end());
    };
    if (straight) go_straight(1.0);
    report.smallest_ccd_step = std::min(report.smallest_ccd_step, bound);
    report.ccd_limited_iterations += bound < 1;
    if (settings.observer) settings.observer({model, terms, c, report.iterations, E, g, H, p, bound, springs_used});
    // The order of what rounding a trial's DOFs and evaluating E change E by: a trial that raises
    // E by less has not been shown to raise it. A body held by a joint has a gradient across the
    // directions it cannot move, where rounding q + α p moves it; near convergence that noise
    // exceeds what the step lowers E by, and halving α could then never find a decrease.
    const double noise = std::numeric_limits<double>::epsilon() * ((g.array() * q.array()).abs().sum() + std::abs(E));
    bool accepted = false;
    Eigen::MatrixX3d x_trial;
    double E_trial = E;
    for (int ls = 0; alpha > 0 && ls < settings.max_line_search; ++ls) {
      ++report.line_search_steps;
      const bool geodesic = !straight;
      if (geodesic) {
        if (ls > 0) bound = bound_chord(alpha);
        if (bound <= 0) {
          go_straight(alpha);
          if (alpha <= 0) break;
        } else if (bound < 1) {
          const double stretch = settings.potential_scale * path->chord_stretch(chord_bounds->islands, chord_bounds->bound, alpha);
          if (stretch >= kChordStretch * alpha * decrease) {
            std::vector<double> own(model.blocks.size());  // each block's α βᵢ
            for (std::size_t b = 0; b < own.size(); ++b)
              own[b] = alpha * chord_bounds->bound[std::size_t(chord_bounds->islands.island(int(b)))];
            path->point(model, own, q_trial);
            chord = q_trial - q;
            chord_bounds = move_bounds(chord, model.surface_step(chord));
          }
          if (chord_bounds->smallest < 1) q_trial = q + chord_bounds->islands.scaled(model, chord, chord_bounds->bound);
        }
      }
      if (straight) q_trial = q + line->islands.scaled(model, p, scale);
      x_trial = model.surface(q_trial);
      update_all(terms, {q_trial, x_trial});
      const bool known = q_trial.size() == q_full.size() && q_trial == q_full;
      E_trial = known ? E_full : total_energy(terms, {q_trial, x_trial});
      if (E_trial <= E + noise) {
        accepted = true;
        break;
      }
      if (small_step) break;
      if (geodesic && !straight) {  // the same α once more, on the straight line
        go_straight(alpha);
        continue;
      }
      alpha *= 0.5;
      for (double& s : scale) s *= 0.5;
      ++report.line_search_halvings;
    }
    if (accepted) {
      q.swap(q_trial);
      x.swap(x_trial);
      bool changed = false;
      for (EnergyTerm* t : terms) changed = t->end_iteration({q, x}) || changed;
      E = changed ? total_energy(terms, {q, x}) : E_trial;
    } else {
      update_all(terms, {q, x});
    }
    if (small_step) {
      report.converged = true;
      ++report.iterations;
      break;
    }
    if (!accepted) {
      report.failure = (alpha > 0 ? "the line search found no decrease of the energy"
                                  : "CCD allowed no step along the Newton direction") + gap_note;
      break;
    }
  }
  if (!report.converged && report.failure.empty())
    report.failure = "the iteration cap (" + std::to_string(settings.max_iterations) + ") was reached" + gap_note;
  report.energy = E;
  return report;
}

}  // namespace stiffsoft
