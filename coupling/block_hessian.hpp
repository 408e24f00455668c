#pragma once
/// @file The global Hessian over affine-body DOFs, assembled in dense 12×12 blocks (one per
/// pair of bodies that interact), and turned into a sparse matrix for the linear solver.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "libabd/affine_body.hpp"

namespace stiffsoft {

/// Symmetric block-sparse matrix with 12×12 blocks; only blocks (i, j) with i ≤ j are stored.
class BlockHessian {
 public:
  /// An empty matrix of num_blocks × num_blocks blocks.
  explicit BlockHessian(int num_blocks);
  /// Adds H to block (i, j), i.e. rows of block i and columns of block j; for i > j the
  /// transpose is added to (j, i).
  void add(int i, int j, const abd::Matrix12d& H);
  /// The upper triangle as a compressed sparse column matrix (12n × 12n).
  Eigen::SparseMatrix<double> upper() const;
  /// The off-diagonal block pairs, sorted: equal lists mean equal sparsity patterns.
  std::vector<std::int64_t> pattern() const;
  /// y = H x for the full symmetric matrix.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;
  /// Number of blocks per side.
  int num_blocks() const { return int(m_diagonal.size()); }

 private:
  std::vector<abd::Matrix12d> m_diagonal;
  std::unordered_map<std::int64_t, abd::Matrix12d> m_off_diagonal;  // key i * n + j, i < j
};

}  // namespace stiffsoft
