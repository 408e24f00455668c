#pragma once
/// @file A quantity's raw values over a run, read from the run's bodies.csv, stats.csv or frames,
/// and reduced to the compared value.

#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include <stiffsoft/study/study_spec.hpp>

namespace stiffsoft::study {

/// Values of a quantity at increasing times.
struct TimeSeries {
  std::vector<double> t;                ///< times (s), increasing
  std::vector<Eigen::VectorXd> values;  ///< one vector per time, all the same size
};

/// The quantity's compared components over the run in `dir` (components selected, "norm"
/// applied, displacement taken). Throws StudyError naming the study file and the quantity's
/// JSON path when the body or column does not exist in the run's output.
TimeSeries read_series(const StudySpec& study, const QuantitySpec& quantity, const std::filesystem::path& dir);

/// Linear interpolation of `series` at time `t`; nan entries when t is outside the series'
/// time range (beyond a relative 1e-9 slack).
Eigen::VectorXd value_at(const TimeSeries& series, double t);

/// The series reduced as the quantity says (all reductions but Trajectory, which returns the
/// last value). Crossing gives the time of the first crossing (nan when there is none).
Eigen::VectorXd reduce(const QuantitySpec& quantity, const TimeSeries& series);

/// The time at which an analytic reference is evaluated for a reduced quantity: the `at` time,
/// else the end of the series.
double reference_time(const QuantitySpec& quantity, const TimeSeries& series);

}  // namespace stiffsoft::study

namespace stiffsoft::study {

/// Column `column` of the run's stats.csv in `dir` as numbers; empty when the file or the
/// column is missing.
std::vector<double> stats_column(const std::filesystem::path& dir, const std::string& column);

}  // namespace stiffsoft::study
