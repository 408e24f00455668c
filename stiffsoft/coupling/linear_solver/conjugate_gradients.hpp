#pragma once
/// @file Preconditioned conjugate gradients to a relative residual, with its report: the Krylov
/// method of the block backend "block_cg" (IC(0) over the DOF blocks, block_cholesky.hpp).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <stiffsoft/coupling/linear_solver/linear_solve_report.hpp>

namespace stiffsoft {

/// p with ‖b − H p‖ ≤ η ‖b‖ by conjugate gradients from p = 0, H x = `multiply`(x) and
/// preconditioner M⁻¹ r = `precondition`(r), at most `max_iterations` iterations in all. CG's
/// recurrence estimates the residual; when it meets η but the residual computed from p does
/// not, CG starts again from p (at most 4 more passes), as the PETSc backend does. Fills the
/// report: iterations, the explicit relative residual, status Converged, Indefinite (a
/// direction with dᵀHd ≤ 0, or bᵀp ≤ 0 at the end, impossible for a positive definite H),
/// IterationCap or Diverged (not finite); p is all NaN unless converged. Every operation is
/// serial but `multiply` and `precondition`, so p does not depend on the threads when theirs
/// do not.
template <class Multiply, class Precondition>
Eigen::VectorXd conjugate_gradients(Multiply&& multiply, Precondition&& precondition, const Eigen::VectorXd& b,
                                    double eta, int max_iterations, const std::string& who,
                                    LinearSolveReport& report) {
  constexpr int kPasses = 5;
  const double b_norm = b.norm();
  const double target = eta * b_norm;
  Eigen::VectorXd p = Eigen::VectorXd::Zero(b.size());
  Eigen::VectorXd r = b;
  report.iterations = 0;
  report.requested_tolerance = eta;
  report.status = LinearSolveStatus::IterationCap;
  report.reason = who + ": iteration cap";
  for (int pass = 0; pass < kPasses && report.iterations < max_iterations; ++pass) {
    Eigen::VectorXd z = precondition(r);
    Eigen::VectorXd d = z;
    double rz = r.dot(z);
    while (r.norm() > target && report.iterations < max_iterations) {
      const Eigen::VectorXd Hd = multiply(d);
      const double curvature = d.dot(Hd);
      if (!(curvature > 0)) {
        report.status = std::isfinite(curvature) ? LinearSolveStatus::Indefinite : LinearSolveStatus::Diverged;
        report.reason = who + (std::isfinite(curvature) ? ": a direction with dᵀHd ≤ 0" : ": not finite");
        break;
      }
      const double alpha = rz / curvature;
      p += alpha * d;
      r -= alpha * Hd;
      z = precondition(r);
      const double rz_next = r.dot(z);
      d = z + (rz_next / rz) * d;
      rz = rz_next;
      ++report.iterations;
    }
    if (report.status == LinearSolveStatus::Indefinite || report.status == LinearSolveStatus::Diverged) break;
    r = b - multiply(p);  // the residual of p itself, not the recurrence's
    if (!std::isfinite(r.norm())) {
      report.status = LinearSolveStatus::Diverged;
      report.reason = who + ": not finite";
      break;
    }
    if (r.norm() <= target) {
      report.status = LinearSolveStatus::Converged;
      report.reason = who + ": converged";
      break;
    }
  }
  const double r_norm = report.status == LinearSolveStatus::Converged ? r.norm() : (b - multiply(p)).norm();
  report.relative_residual = b_norm > 0 ? r_norm / b_norm : r_norm;
  if (report.converged() && b_norm > 0 && !(b.dot(p) > 0)) {
    report.status = LinearSolveStatus::Indefinite;
    report.reason = who + ": converged but bᵀp ≤ 0: H is not positive definite";
  }
  if (!report.converged()) p.setConstant(std::numeric_limits<double>::quiet_NaN());
  return p;
}

}  // namespace stiffsoft
