#pragma once
/// @file Eisenstat–Walker forcing terms for inexact Newton: the relative tolerance η_k of the
/// k-th linear solve, ‖g_k + H_k p_k‖ ≤ η_k ‖g_k‖, follows the convergence of ‖g‖ so early
/// Newton iterations solve loosely and the last ones accurately (Eisenstat & Walker 1996,
/// "Choosing the forcing terms in an inexact Newton method", SIAM J. Sci. Comput. 17(1),
/// choice 2 with its safeguard).

#include <algorithm>
#include <cmath>

namespace stiffsoft {

/// Parameters of the forcing terms: Eisenstat–Walker's choice 2 (γ = 0.9, α = (1+√5)/2, as
/// PETSc's SNES uses) with a tight cap η_max = 1e-3 and η_min = 1e-8.
struct ForcingTermSettings {
  double eta_initial = 0.5;           ///< η_0, for the first Newton iteration of a minimisation (then clamped)
  double gamma = 0.9;                 ///< γ ∈ (0, 1]
  double alpha = 1.6180339887498949;  ///< α ∈ (1, 2]; local convergence then has q-order α
  /// Upper bound; η ≥ 1 would allow p = 0. Measured (docs/linear_solvers.md, "Inexact
  /// Newton"): every Newton iteration also costs assembly, CCD and a line search, which
  /// outweigh a Krylov solve on every scene measured, so loose solves (η_max 0.5) cost more
  /// time in extra Newton iterations (16.4 against 2.0 per step on a 905-body pile) than they
  /// save in the solve; 1e-3 gave exact Newton's iteration count at the least time per step.
  double eta_max = 1e-3;
  double eta_min = 1e-8;             ///< lower bound: below it a Krylov solve only chases round-off
  double safeguard_threshold = 0.1;  ///< apply the safeguard when γ η_{k−1}^α exceeds this
};

/// η_k from ‖g_k‖, ‖g_{k−1}‖ and η_{k−1}:
///   η_k = γ (‖g_k‖ / ‖g_{k−1}‖)^α,
///   η_k ← max(η_k, γ η_{k−1}^α) when γ η_{k−1}^α > 0.1 (safeguard: η must not drop abruptly
///         while the previous one was large, when the decrease of ‖g‖ may be luck),
///   η_k ← clamp(η_k, η_min, η_max).
/// A non-finite or non-positive ‖g_{k−1}‖ (no previous iteration) gives settings.eta_initial.
/// Newton calls it once per iteration with its gradient norms; the first iteration uses
/// settings.eta_initial. Newton's stopping rule is unchanged (it decides on the step, not η).
inline double forcing_term(double g_norm, double g_norm_previous, double eta_previous,
                           const ForcingTermSettings& settings = {}) {
  const ForcingTermSettings& s = settings;
  auto clamp = [&](double eta) { return std::clamp(eta, s.eta_min, s.eta_max); };
  if (!(g_norm_previous > 0) || !std::isfinite(g_norm_previous) || !std::isfinite(g_norm))
    return clamp(s.eta_initial);
  double eta = s.gamma * std::pow(g_norm / g_norm_previous, s.alpha);
  const double previous = s.gamma * std::pow(std::max(eta_previous, 0.0), s.alpha);
  if (previous > s.safeguard_threshold) eta = std::max(eta, previous);
  return clamp(eta);
}

}  // namespace stiffsoft
