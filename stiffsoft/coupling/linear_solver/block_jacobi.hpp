#pragma once
/// @file Block-Jacobi preconditioner over the DOF blocks of q (12×12 for an affine body, 3×3
/// for a soft node): P⁻¹ = blockdiag(H_bb)⁻¹, each block inverted through its Cholesky factor.
/// PETSc 3.18's PCVPBJACOBI needs an AIJ matrix, so the PETSc backend applies this one as a
/// PCSHELL on its BAIJ matrix.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace stiffsoft {

/// The inverses of the diagonal DOF blocks whose rows lie in [row_begin, row_end).
class BlockJacobi {
 public:
  /// Blocks of the given sizes (consecutive from row 0); this rank owns those starting in
  /// [row_begin, row_end), which must not cut a block (throws std::invalid_argument).
  BlockJacobi(const std::vector<int>& block_sizes, int row_begin, int row_end);
  /// Inverts the owned diagonal blocks of H (given by its upper triangle); false when one of
  /// them is not positive definite (then failed_row() is its first row).
  bool compute(const Eigen::SparseMatrix<double>& upper);
  /// y = P⁻¹ x on the owned rows: x and y hold row_end − row_begin values.
  void apply(const double* x, double* y) const;
  /// First row of the block that was not positive definite in the last compute(), or −1.
  int failed_row() const { return m_failed_row; }

 private:
  std::vector<int> m_offsets, m_sizes;  // owned blocks: first row (global), size
  std::vector<std::size_t> m_pool_offsets;
  std::vector<double> m_pool;  // the inverses, column-major, one after the other
  int m_row_begin = 0, m_row_end = 0;
  int m_failed_row = -1;
};

}  // namespace stiffsoft
