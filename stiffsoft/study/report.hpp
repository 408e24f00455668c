#pragma once
/// @file The outputs of a study: study.csv, report.md, plot_data.json, plot.py and the PNG plots.

#include <filesystem>
#include <string>

#include <stiffsoft/study/analysis.hpp>

namespace stiffsoft::study {

/// Writes DIR/study.csv: one row per run and quantity (quantity, series, x, the swept values,
/// hash, value, reference, error, wall_seconds, step_seconds, steps, newton_iterations,
/// linear_iterations, converged, intersection_free, is_reference, cached, exit_code, note).
/// Vector values are written as their components separated by spaces.
void write_csv(const StudySpec& study, const Analysis& analysis, const std::filesystem::path& file);

/// Writes DIR/orders.csv: one row per quantity and series (quantity, series, slope, points,
/// expected, agrees, richardson_order, note); slope and expected are empty when unknown.
void write_orders_csv(const StudySpec& study, const Analysis& analysis, const std::filesystem::path& file);

/// Writes DIR/report.md: per quantity the observed orders (fitted and pairwise) against the
/// expected ones, every run's error and cost, the fastest setting reaching each error decade,
/// and the plots (file names relative to the report).
void write_markdown(const StudySpec& study, const Plan& plan, const Analysis& analysis, const std::filesystem::path& file,
                    const std::string& command_line);

/// Writes DIR/plot_data.json and DIR/plot.py, then runs `python3 plot.py plot_data.json`
/// (matplotlib, Agg backend) which writes `<slug>_error.png` (error against x, log-log, with the
/// fitted slope per series) and `<slug>_frontier.png` (error against the steps' wall time, with the
/// speed/accuracy frontier) for every quantity. Returns an empty string on success, else what
/// went wrong (python3 or matplotlib missing: see DIR/plot.log).
std::string write_plots(const StudySpec& study, const Analysis& analysis, const std::filesystem::path& dir);

/// A file-name-safe form of a quantity name: lower case letters, digits and '_'.
std::string slug(const std::string& name);

}  // namespace stiffsoft::study
