#pragma once
/// @file CHOLMOD Cholesky (SuiteSparse) behind the LinearSolver interface.

#include <memory>

#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>

namespace stiffsoft {

/// Direct sparse Cholesky H = L Lᵀ with CHOLMOD (through Eigen's wrapper): supernodal where
/// the factorisation has enough flops per factor entry for dense blocks to pay (soft meshes),
/// simplicial otherwise (piles of affine bodies, whose factors are sparse and cheap: there the
/// supernodal method's per-supernode BLAS calls cost more than the arithmetic). CHOLMOD's
/// analysis chooses, with its own threshold.
/// Each solve takes one step of iterative refinement; its report gives the explicit relative
/// residual ‖b − H p‖/‖b‖.
class CholmodSolver final : public LinearSolver {
 public:
  /// A solver with nothing analysed yet: call analyze_pattern() first.
  CholmodSolver();
  /// Frees CHOLMOD's factor.
  ~CholmodSolver() override;
  /// See LinearSolver.
  void analyze_pattern(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver.
  bool factorize(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override;
  /// See LinearSolver.
  std::string name() const override { return "cholmod"; }
  /// Floating-point operations of the numeric factorisation, as CHOLMOD's symbolic analysis
  /// predicts them (cholmod_common::fl); 0 before analyze_pattern().
  double factor_flops() const;
  /// Stored entries of the factor L the analysis predicts (cholmod_common::lnz).
  double factor_nonzeros() const;
  /// Whether the last analysis chose the supernodal method (else simplicial).
  bool supernodal() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace stiffsoft
