#pragma once
/// @file IPC's log barrier, written in squared distances (Li et al. 2020, eq. 6, with the
/// d² convention of ipc-toolkit: b(s, ŝ) with s = d², ŝ = d̂²).

#include <cmath>
#include <limits>

namespace stiffsoft::contact {

/// Barrier b(s) = −(s − ŝ)² ln(s / ŝ) for 0 < s < ŝ = d̂², 0 for s ≥ ŝ, +∞ for s ≤ 0.
/// s: squared distance, m²; dhat: activation distance d̂, m. C² at s = ŝ. Units m⁴, so the
/// energy κ b needs κ in N/m³.
inline double barrier(double s, double dhat) {
  const double s_hat = dhat * dhat;
  if (s >= s_hat) return 0.0;
  if (s <= 0.0) return std::numeric_limits<double>::infinity();
  const double ds = s - s_hat;
  return -ds * ds * std::log(s / s_hat);
}

/// b'(s) = −2 (s − ŝ) ln(s/ŝ) − (s − ŝ)²/s, m²; ≤ 0 on (0, ŝ); −∞ for s ≤ 0.
inline double barrier_first_derivative(double s, double dhat) {
  const double s_hat = dhat * dhat;
  if (s >= s_hat) return 0.0;
  if (s <= 0.0) return -std::numeric_limits<double>::infinity();
  const double ds = s - s_hat;
  return -2.0 * ds * std::log(s / s_hat) - ds * ds / s;
}

/// b''(s) = −2 ln(s/ŝ) − 4 (s − ŝ)/s + (s − ŝ)²/s², dimensionless; ≥ 0 on (0, ŝ); +∞ for s ≤ 0.
inline double barrier_second_derivative(double s, double dhat) {
  const double s_hat = dhat * dhat;
  if (s >= s_hat) return 0.0;
  if (s <= 0.0) return std::numeric_limits<double>::infinity();
  const double ds = s - s_hat;
  return -2.0 * std::log(s / s_hat) - 4.0 * ds / s + ds * ds / (s * s);
}

}  // namespace stiffsoft::contact
