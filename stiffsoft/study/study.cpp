#include <stiffsoft/study/study.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include <stiffsoft/study/analysis.hpp>
#include <stiffsoft/study/report.hpp>
#include <stiffsoft/study/runner.hpp>
#include <stiffsoft/study/study_spec.hpp>
#include <stiffsoft/study/sweep.hpp>

namespace stiffsoft::study {

int run_study(const StudyOptions& options) {
  const StudySpec study = load_study(options.study);
  const Plan plan = make_plan(study);
  std::filesystem::create_directories(options.out / "runs");

  const int cores = std::max(1, int(std::thread::hardware_concurrency()));
  RunnerOptions runner;
  runner.binary = options.program.empty() ? std::filesystem::read_symlink("/proc/self/exe") : options.program;
  runner.runs = options.out / "runs";
  runner.jobs = options.jobs > 0 ? options.jobs : cores;
  runner.threads = std::max(1, cores / runner.jobs);
  runner.check = options.check && study.check_intersections;
  std::vector<const RunPlan*> runs;
  for (const RunPlan& r : plan.runs) runs.push_back(&r);
  for (const auto& [key, r] : plan.reference_runs) runs.push_back(&r);
  spdlog::info("study {}: {} runs ({} series × {} values of {}{})", study.name, runs.size(), plan.series.size(),
               study.sweep[study.x].values.size(), study.sweep[study.x].path,
               plan.reference_runs.empty() ? "" : ", plus reference runs");
  const std::map<std::string, RunResult> results = run_all(runs, runner);

  const Analysis analysis = analyse(study, plan, results);
  write_csv(study, analysis, options.out / "study.csv");
  write_orders_csv(study, analysis, options.out / "orders.csv");
  write_markdown(study, plan, analysis, options.out / "report.md",
                 "stiffsoft study " + options.study.string() + " -o " + options.out.string());
  for (const SeriesOrder& o : analysis.orders) {
    spdlog::info("{}{}: observed order {}{}", study.quantities[o.quantity].name, o.series.empty() ? "" : " [" + o.series + "]",
                 o.fit ? std::to_string(o.fit->slope) : std::string("n/a"),
                 o.expected ? " (expected " + std::to_string(*o.expected) + (o.agrees() ? ", agrees)" : ", DISAGREES)") : "");
  }
  const std::string plots = write_plots(study, analysis, options.out);
  spdlog::info("study {}: wrote {}, {}", study.name, (options.out / "study.csv").string(),
               (options.out / "report.md").string());
  if (!plots.empty()) {
    spdlog::error("{}", plots);
    return 1;
  }
  return 0;
}

}  // namespace stiffsoft::study
