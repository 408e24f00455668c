#pragma once
/// @file What the last linear solve of a backend did: how it ended, how many Krylov iterations
/// it took, the relative residual it reached, and whether a fallback solved it instead.

#include <string>

namespace stiffsoft {

/// How a linear solve ended.
enum class LinearSolveStatus {
  NotSolved,             ///< no solve yet since the last factorize()
  Converged,             ///< ‖b − H p‖ ≤ η ‖b‖ reached (a direct solve: succeeded)
  Indefinite,            ///< H (or the preconditioner) is not positive definite: CG saw pᵀHp ≤ 0,
                         ///< KSP_DIVERGED_INDEFINITE_MAT / _PC, or a Cholesky factorisation failed
  PreconditionerFailed,  ///< the preconditioner could not be built or applied (zero pivot, …)
  IterationCap,          ///< the Krylov iteration cap was reached before the tolerance
  Diverged               ///< any other Krylov failure (residual growth, breakdown, NaN or ∞)
};

/// Short lower-case name of a status ("converged", "indefinite", …), for logs.
const char* to_string(LinearSolveStatus status);

/// The record of the last solve() (and of the factorize() before it).
struct LinearSolveReport {
  LinearSolveStatus status = LinearSolveStatus::NotSolved;  ///< how the solve ended
  int iterations = 0;  ///< Krylov iterations, summed over refinement passes; 0 for a direct solve
  /// ‖b − H p‖ / ‖b‖ of the returned p, computed explicitly (not the Krylov estimate)
  double relative_residual = 0;
  double requested_tolerance = 0;  ///< the relative tolerance η asked for (0 for a direct solve)
  std::string reason;              ///< backend's own word for the ending, e.g. "KSP_DIVERGED_INDEFINITE_PC"
  bool fallback_used = false;      ///< the primary method failed and the fallback (CHOLMOD) produced p
  std::string primary_failure;     ///< when fallback_used: why the primary method failed
  double setup_seconds = 0;        ///< wall time of the last factorize() (copy, preconditioner set-up) (s)
  double solve_seconds = 0;        ///< wall time of the last solve() (s)

  /// True when the returned p solves H p = b to the requested tolerance.
  bool converged() const { return status == LinearSolveStatus::Converged; }
};

}  // namespace stiffsoft
