#include <stiffsoft/study/report.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include <stiffsoft/io/atomic_file.hpp>
#include <stiffsoft/study/plot_script.hpp>
#include <stiffsoft/study/runner.hpp>

namespace stiffsoft::study {

namespace {

std::string num(double v, const char* format = "%.4g") {
  if (std::isnan(v)) return "nan";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, v);
  return buffer;
}

std::string vec(const Eigen::VectorXd& v, const char* format = "%.10g") {
  std::string s;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i) s += ' ';
    s += num(v[i], format);
  }
  return s;
}

std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string parameters_text(const StudySpec& study, const RunPlan& run) {
  std::string s;
  for (const SweepParameter& p : study.sweep) s += (s.empty() ? "" : " ") + p.path + "=" + run.parameters.at(p.path).dump();
  return s;
}

std::string reference_text(const StudySpec& study, const QuantitySpec& q) {
  const ReferenceSpec& r = q.reference;
  const std::string& xlabel = study.sweep[study.x].label;
  switch (r.kind) {
    case ReferenceKind::Analytic: {
      std::string e;
      for (const std::string& x : r.expressions) e += (e.empty() ? "" : "; ") + x;
      return (r.builtin.empty() ? "analytic: " : "built-in `" + r.builtin + "`: ") + "`" + e + "`";
    }
    case ReferenceKind::Finest:
      return std::string("the finest run of each series (") + (r.finest_is_largest ? "largest " : "smallest ") + xlabel + ")";
    case ReferenceKind::Richardson:
      return std::string("Richardson extrapolation from the finest runs of each series (") +
             (r.finest_is_largest ? "largest " : "smallest ") + xlabel + "), order " +
             (r.order ? num(*r.order) + " (given)" : "estimated from the three finest");
    case ReferenceKind::Run: return "an extra run with " + r.overrides.dump();
  }
  return "";
}

std::string reduction_text(const QuantitySpec& q) {
  switch (q.reduction) {
    case Reduction::At: return "at t = " + num(q.time) + " s";
    case Reduction::End: return "at the end";
    case Reduction::Max: return "largest over the run";
    case Reduction::Min: return "smallest over the run";
    case Reduction::MaxAbs: return "largest |value| over the run";
    case Reduction::Change: return "change from the first to the last row";
    case Reduction::Crossing: return "first time it crosses " + num(q.crossing_value);
    case Reduction::Trajectory: return "whole trajectory (largest deviation over time)";
  }
  return "";
}

}  // namespace

std::string slug(const std::string& name) {
  std::string s;
  for (char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c))) s += char(std::tolower(static_cast<unsigned char>(c)));
    else if (!s.empty() && s.back() != '_') s += '_';
  }
  while (!s.empty() && s.back() == '_') s.pop_back();
  return s.empty() ? "quantity" : s;
}

void write_csv(const StudySpec& study, const Analysis& analysis, const std::filesystem::path& file) {
  write_file_atomically(file, [&](std::ostream& out) {
    out << "quantity,series,x,parameters,hash,value,reference,error,wall_seconds,step_seconds,steps,newton_iterations,"
           "linear_iterations,converged,intersection_free,is_reference,cached,exit_code,note\n";
    for (const ResultRow& r : analysis.rows) {
      out << csv_cell(study.quantities[r.quantity].name) << ',' << csv_cell(r.plan->series) << ','
          << num(r.plan->x, "%.10g") << ',' << csv_cell(parameters_text(study, *r.plan)) << ',' << r.plan->hash << ','
          << vec(r.value) << ',' << vec(r.reference) << ',' << num(r.error, "%.10g") << ','
          << num(r.result.wall_seconds, "%.4f") << ',' << num(r.cost.step_seconds, "%.4f") << ',' << r.cost.steps << ','
          << r.cost.newton_iterations << ',' << r.cost.linear_iterations << ',' << (r.cost.converged ? 1 : 0) << ','
          << (r.intersection_free() ? 1 : 0) << ',' << (r.is_reference ? 1 : 0) << ',' << (r.result.cached ? 1 : 0)
          << ',' << r.result.exit_code << ',' << csv_cell(r.note) << '\n';
    }
  });
}

void write_orders_csv(const StudySpec& study, const Analysis& analysis, const std::filesystem::path& file) {
  write_file_atomically(file, [&](std::ostream& out) {
    out << "quantity,series,slope,points,expected,agrees,richardson_order,note\n";
    for (const SeriesOrder& o : analysis.orders) {
      out << csv_cell(study.quantities[o.quantity].name) << ',' << csv_cell(o.series) << ','
          << (o.fit ? num(o.fit->slope, "%.6g") : "") << ',' << (o.fit ? o.fit->points : 0) << ','
          << (o.expected ? num(*o.expected, "%.6g") : "") << ',' << (o.agrees() ? 1 : 0) << ','
          << num(o.richardson_order, "%.6g") << ',' << csv_cell(o.note) << '\n';
    }
  });
}

void write_markdown(const StudySpec& study, const Plan& plan, const Analysis& analysis, const std::filesystem::path& file,
                    const std::string& command_line) {
  write_file_atomically(file, [&](std::ostream& out) {
    const SweepParameter& xp = study.sweep[study.x];
    out << "# Study `" << study.name << "`\n\n";
    if (!study.description.empty()) out << study.description << "\n\n";
    out << "- Command: `" << command_line << "`\n";
    out << "- Base scene: `" << study.scene.filename().string() << "`";
    if (!study.set.empty()) out << ", with " << study.set.dump();
    out << "\n- Swept: ";
    for (std::size_t i = 0; i < study.sweep.size(); ++i) {
      out << (i ? "; " : "") << "`" << study.sweep[i].path << "` ∈ {";
      for (std::size_t k = 0; k < study.sweep[i].values.size(); ++k)
        out << (k ? ", " : "") << study.sweep[i].values[k].dump();
      out << "}" << (int(i) == study.x ? " (x axis)" : "");
    }
    int runs = int(plan.runs.size() + plan.reference_runs.size());
    double wall = 0;
    std::set<std::string> seen;
    int failed_steps = 0, intersecting = 0, cached = 0;
    for (const ResultRow& r : analysis.rows) {
      if (!seen.insert(r.plan->hash).second) continue;
      wall += r.result.wall_seconds;
      failed_steps += r.cost.converged ? 0 : 1;
      intersecting += r.intersection_free() ? 0 : 1;
      cached += r.result.cached ? 1 : 0;
    }
    out << "\n- Runs: " << runs << " (" << cached << " from the cache); total wall time of the sweep runs " << num(wall, "%.1f")
        << " s (summed over runs; they ran in parallel)\n";
    out << "- Runs with a step that did not converge: " << failed_steps << "; runs with intersecting frames (or unchecked): "
        << intersecting << "\n\n";
    for (int q = 0; q < int(study.quantities.size()); ++q) {
      const QuantitySpec& quantity = study.quantities[q];
      const std::string unit = quantity.unit.empty() ? "" : " (" + quantity.unit + ")";
      const bool relative = quantity.normalization != Normalization::None;
      out << "## " << quantity.name << "\n\n";
      out << "- Value: " << reduction_text(quantity) << "; error: " << (relative ? "relative " : "")
          << "Euclidean norm of the difference" << (relative ? "" : unit) << "\n";
      out << "- Reference: " << reference_text(study, quantity) << "\n\n";
      out << "![error against " << xp.label << "](" << slug(quantity.name) << "_error.png) ![speed/accuracy]("
          << slug(quantity.name) << "_frontier.png)\n\n";
      out << "| series | observed order (fit) | expected | pairwise slopes | verdict |\n|---|---|---|---|---|\n";
      for (const SeriesOrder& o : analysis.orders) {
        if (o.quantity != q) continue;
        std::string pairwise;
        for (double s : o.pairwise) pairwise += (pairwise.empty() ? "" : ", ") + num(s, "%.2f");
        std::string verdict;
        if (!o.fit) verdict = "no fit" + (o.note.empty() ? "" : ": " + o.note);
        else if (!o.expected) verdict = "—";
        else verdict = o.agrees() ? "agrees" : "**disagrees** (see the discussion in docs/accuracy.md)";
        out << "| " << (o.series.empty() ? "all" : o.series) << " | " << (o.fit ? num(o.fit->slope, "%.2f") : "—")
            << (o.fit ? " (" + std::to_string(o.fit->points) + " points)" : "") << " | "
            << (o.expected ? num(*o.expected, "%.3g") : "—") << " | " << pairwise << " | " << verdict
            << (o.richardson_order != 0 ? "; Richardson order " + num(o.richardson_order, "%.2f") : "") << " |\n";
      }
      out << "\n| series | " << xp.label << " | value | reference | error | wall (s) | steps (s) | Newton it. | linear it. | converged | intersection-free |\n";
      out << "|---|---|---|---|---|---|---|---|---|---|---|\n";
      for (const ResultRow& r : analysis.rows) {
        if (r.quantity != q) continue;
        out << "| " << (r.plan->series.empty() ? "—" : r.plan->series) << " | " << num(r.plan->x, "%.4g") << " | "
            << vec(r.value, "%.6g") << " | " << vec(r.reference, "%.6g") << " | "
            << (r.is_reference ? "(reference)" : num(r.error, "%.3e")) << (r.note.empty() ? "" : " " + r.note) << " | "
            << num(r.result.wall_seconds, "%.2f") << " | " << num(r.cost.step_seconds, "%.2f") << " | "
            << r.cost.newton_iterations << " | " << r.cost.linear_iterations << " | " << (r.cost.converged ? "yes" : "**no**")
            << " | " << (r.result.check_code == -1 ? "not checked" : r.intersection_free() ? "yes" : "**no**") << " |\n";
      }
      // Fastest setting that reaches each error decade.
      std::vector<const ResultRow*> candidates;
      double lo = std::numeric_limits<double>::infinity(), hi = 0;
      for (const ResultRow& r : analysis.rows)
        if (r.quantity == q && !r.is_reference && std::isfinite(r.error) && r.error > 0 && r.cost.converged) {
          candidates.push_back(&r);
          lo = std::min(lo, r.error);
          hi = std::max(hi, r.error);
        }
      if (!candidates.empty()) {
        out << "\nFastest converged setting reaching each error level (cost: the steps' wall time, without start-up and output):\n\n| error ≤ | fastest setting | steps (s) | its error |\n|---|---|---|---|\n";
        for (int e = int(std::ceil(std::log10(hi))); e >= int(std::floor(std::log10(lo))); --e) {
          const double level = std::pow(10.0, e);
          const ResultRow* best = nullptr;
          for (const ResultRow* r : candidates)
            if (r->error <= level && (!best || r->cost.step_seconds < best->cost.step_seconds)) best = r;
          if (!best) continue;
          out << "| 1e" << e << " | " << (best->plan->series.empty() ? "" : best->plan->series + ", ") << xp.label << " = "
              << num(best->plan->x, "%.4g") << " | " << num(best->cost.step_seconds, "%.3g") << " | "
              << num(best->error, "%.2e") << " |\n";
        }
      }
      out << "\n";
    }
  });
}

std::string write_plots(const StudySpec& study, const Analysis& analysis, const std::filesystem::path& dir) {
  nlohmann::json data{{"study", study.name}, {"quantities", nlohmann::json::array()}};
  for (int q = 0; q < int(study.quantities.size()); ++q) {
    const QuantitySpec& quantity = study.quantities[q];
    nlohmann::json jq{{"name", quantity.name},
                      {"slug", slug(quantity.name)},
                      {"unit", quantity.unit},
                      {"relative", quantity.normalization != Normalization::None},
                      {"x_label", study.sweep[study.x].label},
                      {"series", nlohmann::json::array()}};
    for (const SeriesOrder& o : analysis.orders) {
      if (o.quantity != q) continue;
      nlohmann::json s{{"label", o.series}, {"x", nlohmann::json::array()}, {"error", nlohmann::json::array()},
                       {"wall", nlohmann::json::array()}, {"slope", nullptr}, {"scale", nullptr}};
      for (const ResultRow& r : analysis.rows) {
        if (r.quantity != q || r.plan->series != o.series || r.is_reference) continue;
        s["x"].push_back(r.plan->x);
        s["error"].push_back(std::isfinite(r.error) ? nlohmann::json(r.error) : nlohmann::json());
        s["wall"].push_back(r.cost.step_seconds);
      }
      if (o.fit) {
        s["slope"] = o.fit->slope;
        s["scale"] = std::exp(o.fit->intercept);
      }
      jq["series"].push_back(s);
    }
    data["quantities"].push_back(jq);
  }
  write_file_atomically(dir / "plot_data.json", [&](std::ostream& os) { os << data.dump(1) << '\n'; });
  write_file_atomically(dir / "plot.py", [&](std::ostream& os) { os << kPlotScript; });
  // The Debian interpreter first: python3-matplotlib is installed for it, while a python3 earlier
  // in PATH (pyenv, a virtual environment) may lack matplotlib.
  const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const int rc = run_process({python, (dir / "plot.py").string(), (dir / "plot_data.json").string()}, dir / "plot.log");
  if (rc == 0) return "";
  return "the plots were not drawn: `" + python + " plot.py` exited with " + std::to_string(rc) +
         " (is python3-matplotlib installed? scripts/setup.sh installs it); see " + (dir / "plot.log").string() +
         ". study.csv and report.md are written.";
}

}  // namespace stiffsoft::study
