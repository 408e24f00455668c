#pragma once
/// @file The linear-solver interface of Newton's step: analyse a sparsity pattern once, then
/// factor (or set up) and solve many systems with it. Backends plug in behind it.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

namespace stiffsoft {

/// Solves H p = b for symmetric positive (semi-)definite H given by its upper triangle.
class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Symbolic analysis of the upper triangle's pattern; called again only when it changes.
  virtual void analyze_pattern(const Eigen::SparseMatrix<double>& upper) = 0;
  /// Numeric factorisation (or set-up); returns false when H is not positive definite
  /// (numerically), in which case solve() must not be called.
  virtual bool factorize(const Eigen::SparseMatrix<double>& upper) = 0;
  /// The solution of H p = b with the last factorised H.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& b) = 0;
  /// The backend's name, for logs and stats.
  virtual std::string name() const = 0;
};

/// The backend called `name` ("cholmod"); throws std::invalid_argument for an unknown one.
std::unique_ptr<LinearSolver> make_linear_solver(const std::string& name);

}  // namespace stiffsoft
