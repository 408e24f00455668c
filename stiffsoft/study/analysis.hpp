#pragma once
/// @file Errors of every run against its reference, costs, and observed orders per series.

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <stiffsoft/study/order_fit.hpp>
#include <stiffsoft/study/runner.hpp>
#include <stiffsoft/study/study_spec.hpp>
#include <stiffsoft/study/sweep.hpp>

namespace stiffsoft::study {

/// What a run cost, from its stats.csv.
struct RunCost {
  int steps = 0;                 ///< steps taken
  double newton_iterations = 0;  ///< total over the steps
  double linear_iterations = 0;  ///< total over the steps
  double step_seconds = 0;       ///< sum of the steps' wall times (s), without start-up and output
  bool converged = false;        ///< every step's Newton converged
};

/// One run × one quantity.
struct ResultRow {
  int quantity = 0;                  ///< index into StudySpec::quantities
  const RunPlan* plan = nullptr;     ///< the run
  RunResult result;                  ///< how it ran
  RunCost cost;                      ///< what it cost
  Eigen::VectorXd value;             ///< the reduced quantity (empty when the run failed)
  Eigen::VectorXd reference;         ///< its reference (at the end time for trajectories)
  double error = 0;                  ///< the error (nan when unknown)
  bool is_reference = false;         ///< this run is the reference itself (Finest): error 0 by construction
  std::string note;                  ///< why the error is unknown, if it is
  /// Every frame intersection-free according to `stiffsoft check` (false when not checked).
  bool intersection_free() const { return result.check_code == 0; }
};

/// The observed order of one series of one quantity.
struct SeriesOrder {
  int quantity = 0;                      ///< index into StudySpec::quantities
  std::string series;                    ///< series label
  std::optional<LogLogFit> fit;          ///< least squares over the series' errors (reference run excluded)
  std::vector<double> x;                 ///< x values in increasing order
  std::vector<double> pairwise;          ///< slopes between consecutive x (size x.size() − 1; nan where undefined)
  std::optional<double> expected;        ///< the study's expected order, if given
  double richardson_order = 0;           ///< Richardson: the order used (given or estimated); 0 otherwise
  std::string note;                      ///< e.g. why Richardson or the fit was not possible
  /// True when there is an expected order and the fitted slope is within 0.25 of it.
  bool agrees() const { return expected && fit && std::abs(fit->slope - *expected) <= 0.25; }
};

/// Everything the report needs.
struct Analysis {
  std::vector<ResultRow> rows;       ///< per run and quantity, in plan order, quantity-major
  std::vector<SeriesOrder> orders;   ///< per quantity and series
};

/// Reads every run's outputs and computes values, references, errors, costs and orders.
/// Throws StudyError when a quantity names a body or column the runs do not have.
Analysis analyse(const StudySpec& study, const Plan& plan, const std::map<std::string, RunResult>& results);

}  // namespace stiffsoft::study
