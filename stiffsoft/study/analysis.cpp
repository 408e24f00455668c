#include <stiffsoft/study/analysis.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include <stiffsoft/study/time_series.hpp>

namespace stiffsoft::study {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

RunCost cost_of(const std::filesystem::path& dir) {
  RunCost c;
  const std::vector<double> newton = stats_column(dir, "newton_iterations"),
                            linear = stats_column(dir, "linear_iterations"),
                            seconds = stats_column(dir, "seconds_step"),
                            converged = stats_column(dir, "converged");
  c.steps = int(newton.size());
  for (double v : newton) c.newton_iterations += v;
  for (double v : linear) c.linear_iterations += v;
  for (double v : seconds) c.step_seconds += v;
  c.converged = !converged.empty();
  for (double v : converged) c.converged = c.converged && v == 1.0;
  return c;
}

bool run_ok(const RunResult& r) { return r.exit_code == 0 || r.exit_code == 3; }

/// The analytic reference's components at time t for run x.
Eigen::VectorXd analytic(const StudySpec& study, const QuantitySpec& q, double t, double x) {
  Variables vars = study.constants;
  vars["t"] = t;
  vars["x"] = x;
  Eigen::VectorXd r(q.reference.expressions.size());
  for (std::size_t i = 0; i < q.reference.expressions.size(); ++i) {
    try {
      r[Eigen::Index(i)] = evaluate(q.reference.expressions[i], vars);
    } catch (const std::exception& e) {
      throw StudyError(study.file.string() + ": " + q.json_path + "/reference: " + e.what() +
                       " (names: constants, t, x)");
    }
  }
  return r;
}

/// Fineness of x: larger is finer.
double fineness(const ReferenceSpec& ref, double x) { return ref.finest_is_largest ? x : 1.0 / x; }

}  // namespace

Analysis analyse(const StudySpec& study, const Plan& plan, const std::map<std::string, RunResult>& results) {
  Analysis analysis;
  std::map<std::string, RunCost> costs;
  std::map<std::string, TimeSeries> series_cache;  // by quantity index + hash
  auto series_of = [&](int q, const RunPlan& run) -> const TimeSeries* {
    const RunResult& r = results.at(run.hash);
    if (!run_ok(r)) return nullptr;
    const std::string key = std::to_string(q) + "|" + run.hash;
    auto it = series_cache.find(key);
    if (it == series_cache.end())
      it = series_cache.emplace(key, read_series(study, study.quantities[q], r.dir)).first;
    return &it->second;
  };
  for (int q = 0; q < int(study.quantities.size()); ++q) {
    const QuantitySpec& quantity = study.quantities[q];
    const ReferenceSpec& ref = quantity.reference;
    for (const std::string& label : plan.series) {
      std::vector<const RunPlan*> runs;
      for (const RunPlan& r : plan.runs)
        if (r.series == label) runs.push_back(&r);
      std::sort(runs.begin(), runs.end(), [](const RunPlan* a, const RunPlan* b) { return a->x < b->x; });
      SeriesOrder order;
      order.quantity = q;
      order.series = label;
      for (const auto* expected : {&quantity.expected_order, &study.expected_order}) {
        if (order.expected) break;
        if (expected->contains(label)) order.expected = expected->at(label);
        else if (expected->contains("")) order.expected = expected->at("");
      }
      // The reference: a value (reduced quantities) or a series (trajectories); nullopt: unknown.
      std::optional<Eigen::VectorXd> ref_value;
      const TimeSeries* ref_series = nullptr;
      const RunPlan* ref_run = nullptr;
      if (ref.kind == ReferenceKind::Finest || ref.kind == ReferenceKind::Richardson) {
        std::vector<const RunPlan*> finest = runs;
        std::sort(finest.begin(), finest.end(),
                  [&](const RunPlan* a, const RunPlan* b) { return fineness(ref, a->x) > fineness(ref, b->x); });
        if (ref.kind == ReferenceKind::Finest) {
          ref_run = finest.front();
          ref_series = series_of(q, *ref_run);
          if (ref_series) ref_value = reduce(quantity, *ref_series);
          else order.note = "the finest run failed: no reference";
        } else if (quantity.reduction == Reduction::Trajectory) {
          throw StudyError(study.file.string() + ": " + quantity.json_path +
                           "/reference: Richardson extrapolation applies to reduced values, not to trajectories");
        } else {
          const std::size_t needed = ref.order ? 2 : 3;
          std::vector<Eigen::VectorXd> f;
          for (std::size_t i = 0; i < finest.size() && f.size() < needed; ++i) {
            const TimeSeries* s = series_of(q, *finest[i]);
            if (!s) break;
            f.push_back(reduce(quantity, *s));
          }
          if (f.size() < needed) {
            order.note = "Richardson needs the " + std::to_string(needed) + " finest runs to succeed";
          } else {
            const double r = fineness(ref, finest[0]->x) / fineness(ref, finest[1]->x);
            double p = ref.order ? *ref.order : kNaN;
            if (!ref.order) {
              const double r2 = fineness(ref, finest[1]->x) / fineness(ref, finest[2]->x);
              if (std::abs(r2 / r - 1) > 0.02)
                throw StudyError(study.file.string() + ": " + quantity.json_path +
                                 "/reference: Richardson without a given order needs the three finest x in a constant "
                                 "ratio; give \"order\" or such values");
              p = three_point_order(f[0], f[1], f[2], r);
            }
            order.richardson_order = p;
            if (std::isfinite(p) && p > 0) ref_value = richardson_extrapolate(f[0], f[1], r, p);
            else order.note = "Richardson: the estimated order is not positive (values not in the asymptotic range)";
          }
        }
      } else if (ref.kind == ReferenceKind::Run) {
        const RunPlan& extra = plan.reference_runs.at(std::to_string(q) + "|" + label);
        ref_series = series_of(q, extra);
        if (ref_series) ref_value = reduce(quantity, *ref_series);
        else order.note = "the reference run failed (see " + results.at(extra.hash).dir.string() + "/run.log)";
      }
      std::vector<double> xs, errors;
      for (const RunPlan* run : runs) {
        ResultRow row;
        row.quantity = q;
        row.plan = run;
        row.result = results.at(run->hash);
        if (!costs.contains(run->hash)) costs[run->hash] = cost_of(row.result.dir);
        row.cost = costs.at(run->hash);
        row.is_reference = run == ref_run;
        row.error = kNaN;
        const TimeSeries* s = series_of(q, *run);
        if (!s) {
          row.note = "run failed (exit " + std::to_string(row.result.exit_code) + ")";
        } else {
          row.value = reduce(quantity, *s);
          if (quantity.reduction == Reduction::Trajectory) {
            double worst = 0, scale = 0;
            int compared = 0;
            for (std::size_t k = 0; k < s->t.size(); ++k) {
              Eigen::VectorXd r;
              if (ref.kind == ReferenceKind::Analytic) r = analytic(study, quantity, s->t[k], run->x);
              else if (ref_series) r = value_at(*ref_series, s->t[k]);
              else break;
              if (!r.allFinite()) continue;
              worst = std::max(worst, (s->values[k] - r).norm());
              scale = std::max(scale, r.norm());
              ++compared;
              if (k + 1 == s->t.size()) row.reference = r;
            }
            if (compared > 0) {
              row.error = worst;
              if (quantity.normalization == Normalization::Reference) row.error /= scale;
            } else {
              row.note = "no reference over this run's times";
            }
          } else {
            if (ref.kind == ReferenceKind::Analytic) row.reference = analytic(study, quantity, reference_time(quantity, *s), run->x);
            else if (ref_value) row.reference = *ref_value;
            if (row.reference.size() == row.value.size() && row.value.size() > 0) {
              row.error = (row.value - row.reference).norm();
              if (quantity.normalization == Normalization::Reference) row.error /= row.reference.norm();
            } else {
              row.note = order.note.empty() ? "no reference" : order.note;
            }
          }
          if (quantity.normalization == Normalization::Initial && std::isfinite(row.error)) {
            row.error /= s->values.front().norm();
          }
          if (!row.value.allFinite() && row.note.empty())
            row.note = quantity.reduction == Reduction::Crossing ? "no crossing" : "value not finite";
        }
        if (!row.is_reference) {
          xs.push_back(run->x);
          errors.push_back(row.error);
        }
        analysis.rows.push_back(row);
      }
      order.fit = fit_log_log(xs, errors);
      for (const RunPlan* run : runs) order.x.push_back(run->x);
      for (std::size_t i = 0; i + 1 < runs.size(); ++i) {
        const auto find = [&](const RunPlan* p) {
          for (const ResultRow& r : analysis.rows)
            if (r.quantity == q && r.plan == p) return r;
          return ResultRow{};
        };
        const ResultRow a = find(runs[i]), b = find(runs[i + 1]);
        double slope = kNaN;
        if (!a.is_reference && !b.is_reference && a.error > 0 && b.error > 0 && runs[i + 1]->x != runs[i]->x)
          slope = std::log(b.error / a.error) / std::log(runs[i + 1]->x / runs[i]->x);
        order.pairwise.push_back(slope);
      }
      analysis.orders.push_back(order);
    }
  }
  return analysis;
}

}  // namespace stiffsoft::study
