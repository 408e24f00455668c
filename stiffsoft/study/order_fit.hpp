#pragma once
/// @file Observed orders of convergence and Richardson extrapolation.

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace stiffsoft::study {

/// A straight line log e = slope · log x + intercept fitted by least squares.
struct LogLogFit {
  double slope = 0;      ///< the observed order (error ∝ x^slope)
  double intercept = 0;  ///< natural log of the constant
  int points = 0;        ///< points used (those with finite x > 0 and e > 0)
};

/// Least-squares fit of log e against log x over the points with x > 0 and e > 0 (finite).
/// Fewer than two such points (or all x equal) give std::nullopt.
std::optional<LogLogFit> fit_log_log(const std::vector<double>& x, const std::vector<double>& e);

/// Richardson extrapolation: f1 is the value at the finest parameter, f2 at a parameter r
/// times coarser (r > 1), p the order: f1 + (f1 − f2) / (rᵖ − 1).
Eigen::VectorXd richardson_extrapolate(const Eigen::VectorXd& f1, const Eigen::VectorXd& f2, double r, double p);

/// The order estimated from three values at parameters in constant ratio r > 1 (f1 finest):
/// log(‖f3 − f2‖ / ‖f2 − f1‖) / log r; nan when a difference is zero.
double three_point_order(const Eigen::VectorXd& f1, const Eigen::VectorXd& f2, const Eigen::VectorXd& f3, double r);

}  // namespace stiffsoft::study
