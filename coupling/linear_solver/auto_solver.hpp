#pragma once
/// @file The "auto" linear solver: CHOLMOD when its factorisation is cheap, PETSc's default
/// Krylov method otherwise, decided at every analyze_pattern() from CHOLMOD's own prediction.

#include <memory>

#include "coupling/linear_solver/linear_solver.hpp"

namespace stiffsoft {

/// Rows from which "auto" takes the Krylov method without asking CHOLMOD (its symbolic
/// analysis alone costs about a second there).
constexpr int kAutoKrylovRows = 100000;

/// Predicted factorisation flops (CHOLMOD's symbolic analysis, cholmod_common::fl) up to which
/// "auto" keeps CHOLMOD. From bench/linear_solver_bench (docs/benchmarks.md, "Linear solvers"):
/// CHOLMOD's factorisation ran at roughly 1 Gflop/s here (reference BLAS, 2 busy cores), and
/// CG with ICC solved the systems where CHOLMOD needs more than ~3e7 flops faster.
constexpr double kAutoCholmodFlops = 3e7;

/// Delegates to CHOLMOD or to PETSc (default_petsc_method()): rows ≥ kAutoKrylovRows → PETSc;
/// otherwise CHOLMOD analyses the pattern and is kept when it predicts at most
/// kAutoCholmodFlops for the factorisation. Re-decides whenever the pattern is analysed.
class AutoSolver final : public LinearSolver {
 public:
  /// Nothing chosen yet.
  AutoSolver();
  /// Frees the chosen backend.
  ~AutoSolver() override;
  /// Chooses the backend (see the class comment), which then has analysed the pattern.
  void analyze_pattern(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver.
  bool factorize(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override;
  /// "auto→" followed by the chosen backend's name, e.g. "auto→cholmod".
  std::string name() const override;
  /// Kept and passed on to a Krylov backend.
  void set_relative_tolerance(double eta) override;
  /// True when the chosen backend is iterative.
  bool is_iterative() const override;
  /// Kept and passed on to the chosen backend.
  void set_block_sizes(const std::vector<int>& sizes) override;

 private:
  std::unique_ptr<LinearSolver> m_backend;
  bool m_krylov = false;
  double m_eta = 0;
  std::vector<int> m_block_sizes;
};

}  // namespace stiffsoft
