#pragma once
/// @file The block Cholesky factorisation (block_cholesky.hpp) behind the LinearSolver
/// interface: "block_cholesky", and what "auto" takes for piles of affine bodies.

#include <Eigen/SparseCore>
#include <vector>

#include <stiffsoft/coupling/linear_solver/block_cholesky.hpp>
#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>

namespace stiffsoft {

/// Direct sparse Cholesky over the DOF blocks (set_block_sizes(); without them the blocks are
/// inferred from the pattern, infer_block_sizes()), or over the blocks analyze_blocks() is
/// given. Each solve takes one step of iterative refinement, its residual a block product; its
/// report gives the explicit relative residual ‖b − H p‖/‖b‖.
class BlockCholeskySolver final : public LinearSolver {
 public:
  /// See LinearSolver.
  void analyze_pattern(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver.
  bool factorize(const Eigen::SparseMatrix<double>& upper) override;
  /// Analyses the blocks in place (the block sizes are H's).
  void analyze_blocks(const BlockUpper& H) override;
  /// Copies the blocks straight into the factor.
  bool factorize_blocks(const BlockUpper& H, double shift) override;
  /// See LinearSolver.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override;
  /// See LinearSolver.
  std::string name() const override { return "block_cholesky"; }
  /// The DOF blocks of the next analysis (12 for an affine body, 3 for a soft node).
  void set_block_sizes(const std::vector<int>& sizes) override { m_sizes = sizes; }
  /// Floating-point operations of one factorisation (the symbolic analysis' count).
  double factor_flops() const { return m_factor.flops(); }

 private:
  BlockCholesky m_factor;
  std::vector<int> m_sizes;
  bool m_factorized = false;

  /// Runs factorize (a call of m_factor's) and fills the report.
  template <class Factorize>
  bool timed_factorize(Factorize&& factorize);
};

}  // namespace stiffsoft
