#pragma once
/// @file A direct solve followed by one step of iterative refinement, with its report: what the
/// Cholesky backends (CHOLMOD, the block factorisation) share.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <limits>
#include <string>

#include <stiffsoft/coupling/linear_solver/linear_solve_report.hpp>

namespace stiffsoft {

/// p = F⁻¹ b with H x = `multiply`(x) and F⁻¹ = `solve` (a factorisation of H), then, where
/// the residual is above kRefineAbove ‖b‖, one step of iterative refinement p += F⁻¹ (b − H p),
/// which brings the error from about cond(H) ε towards a few ε for one more pair of triangular
/// solves. Newton's tightest tolerances need it (without it a hinged pendulum in joints_test
/// stalled at 2.5e-8 m/s against its 1e-8 m/s tolerance); the piles' first solves leave
/// residuals of 6e-15 ‖b‖ (median) and at most 5e-13 ‖b‖, where it changed nothing but the cost.
/// Sets the report's residual ‖b − H p‖/‖b‖, status and reason (`who` names the backend);
/// a p that is not finite is returned as all NaN with status Diverged.
template <class Multiply, class Solve>
Eigen::VectorXd refined_solve(Multiply&& multiply, const Eigen::VectorXd& b, Solve&& solve,
                              const std::string& who, LinearSolveReport& report) {
  constexpr double kRefineAbove = 1e-12;
  const double b_norm = b.norm();
  Eigen::VectorXd p = solve(b);
  Eigen::VectorXd r = b - multiply(p);
  if (!(r.norm() <= kRefineAbove * b_norm)) {  // NaN refines too, and stays NaN
    p += solve(r);
    r = b - multiply(p);
  }
  report.relative_residual = b_norm > 0 ? r.norm() / b_norm : r.norm();
  report.iterations = 0;
  if (p.allFinite()) {
    report.status = LinearSolveStatus::Converged;
    report.reason = who + ": solved";
  } else {
    report.status = LinearSolveStatus::Diverged;
    report.reason = who + ": the solution is not finite";
    p.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  return p;
}

}  // namespace stiffsoft
