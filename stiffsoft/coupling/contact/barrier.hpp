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

/// The Gauss–Newton curvature of the barrier along the squared distance: with B(d) = b(d²),
/// B″(d) ∇d ∇dᵀ = c ∇d² ∇d²ᵀ for c = B″(d)/(4d²) = b''(s) + b'(s)/(2s), clamped at 0 (B is
/// convex in d on (0, d̂) for IPC's barrier, so the clamp only guards round-off), m⁻².
inline double barrier_gauss_newton_coefficient(double s, double dhat) {
  if (s >= dhat * dhat) return 0.0;
  if (s <= 0.0) return std::numeric_limits<double>::infinity();
  const double c = barrier_second_derivative(s, dhat) + barrier_first_derivative(s, dhat) / (2.0 * s);
  return c > 0.0 ? c : 0.0;
}

}  // namespace stiffsoft::contact
