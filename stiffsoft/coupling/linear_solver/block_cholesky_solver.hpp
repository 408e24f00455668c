#pragma once
/// @file The block Cholesky factorisation (block_cholesky.hpp) behind the LinearSolver
/// interface: "block_cholesky", and what "auto" takes for piles of affine bodies.

#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include <stiffsoft/coupling/linear_solver/block_cholesky.hpp>
#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>

namespace stiffsoft {

/// Over the DOF blocks (set_block_sizes(); without them the blocks are inferred from the
/// pattern, infer_block_sizes()), or over the blocks analyze_blocks() is given, one of:
///  - "block_cholesky" (Fill::Complete): the direct sparse Cholesky factorisation; each solve
///    takes one step of iterative refinement, its residual a block product;
///  - "block_cg" (Fill::None): conjugate gradients to the relative tolerance η
///    (set_relative_tolerance()), preconditioned by IC(0) over the blocks. An IC(0) that breaks
///    down on a positive definite H is built again from H + α diag(H), α = 1e-3, 1e-2, … 1;
///    a solve CG cannot finish (iteration cap, negative curvature) falls back to the exact
///    factor of the same H (report.fallback_used), as the PETSc backend falls back to CHOLMOD.
/// Either report gives the explicit relative residual ‖b − H p‖/‖b‖. Both are parallel over
/// independent columns and give the same p bit for bit whatever the thread count.
class BlockCholeskySolver final : public LinearSolver {
 public:
  /// The direct factorisation, or with Fill::None the Krylov method.
  explicit BlockCholeskySolver(BlockCholesky::Fill fill = BlockCholesky::Fill::Complete)
      : m_factor(fill), m_krylov(fill == BlockCholesky::Fill::None) {}
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
  /// "block_cholesky" or "block_cg".
  std::string name() const override { return m_krylov ? "block_cg" : "block_cholesky"; }
  /// η of the Krylov method's solves (the direct one ignores it).
  void set_relative_tolerance(double eta) override { m_eta = eta; }
  /// True for "block_cg".
  bool is_iterative() const override { return m_krylov; }
  /// The DOF blocks of the next analysis (12 for an affine body, 3 for a soft node).
  void set_block_sizes(const std::vector<int>& sizes) override { m_sizes = sizes; }
  /// Floating-point operations of one factorisation (the symbolic analysis' count).
  double factor_flops() const { return m_factor.flops(); }

 private:
  BlockCholesky m_factor;
  bool m_krylov;
  double m_eta = kKrylovRelativeTolerance;
  std::vector<int> m_sizes;
  bool m_factorized = false;
  std::unique_ptr<BlockCholesky> m_fallback;  // block_cg's exact factor, made when CG fails

  /// Runs factorize (a call of m_factor's) and fills the report.
  template <class Factorize>
  bool timed_factorize(Factorize&& factorize);
  /// factor(0) (a factorisation of m_factor's with that boost), and for IC(0) again with a
  /// growing boost while it fails.
  template <class Factor>
  bool factorize_with_boost(Factor&& factor);
  /// After CG failed on b (the report says why): p from the exact factor of the H CG was given.
  Eigen::VectorXd fallback_solve(const Eigen::VectorXd& b);
};

}  // namespace stiffsoft
