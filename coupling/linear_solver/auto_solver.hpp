#pragma once
/// @file The "auto" linear solver: CHOLMOD for small systems, a PETSc Krylov solver for large
/// ones, chosen from the number of rows at every analyze_pattern().

#include <memory>

#include "coupling/linear_solver/linear_solver.hpp"

namespace stiffsoft {

/// Rows from which "auto" picks PETSc's default Krylov method over CHOLMOD (see
/// docs/benchmarks.md: the measured cross-over, rounded).
constexpr int kAutoKrylovRows = 200000;

/// Delegates to CHOLMOD below kAutoKrylovRows rows and to PETSc (default_petsc_method())
/// from there on; re-decides whenever the pattern is analysed.
class AutoSolver final : public LinearSolver {
 public:
  /// Nothing chosen yet.
  AutoSolver();
  /// Frees the chosen backend.
  ~AutoSolver() override;
  /// Chooses the backend from upper.rows(), then lets it analyse.
  void analyze_pattern(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver.
  bool factorize(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override;
  /// "auto" followed by the chosen backend's name, e.g. "auto→cholmod".
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
