#pragma once
/// @file The upper triangle of a symmetric matrix over dense DOF blocks, read where its owner
/// keeps it: what a block backend factorises without a compressed sparse copy, and the
/// compressed copy for every other backend.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

namespace stiffsoft {

/// The stored off-diagonal blocks of an upper triangle by block row: what a product with the
/// whole symmetric matrix reads the lower triangle from. It depends on the pattern only
/// (block_rows()), so whoever multiplies by one pattern many times keeps it.
struct BlockRows {
  std::vector<int> starts{0};              ///< block row i's entries are [starts[i], starts[i + 1])
  std::vector<std::array<int, 2>> blocks;  ///< (stored block k, its block column), by ascending column
};

/// H over DOF blocks (block b holds DOFs [offsets[b], offsets[b + 1])) as its stored blocks
/// (i, j), i ≤ j, column by column: column j's are k ∈ [column_starts[j], column_starts[j + 1])
/// with block row rows[k], ascending, and values[k] pointing at size_i × size_j numbers,
/// column-major. Of a diagonal block only the upper triangle is read. Blocks not stored are
/// zero. A view: the pointers belong to the owner (BlockHessian) or to GatheredBlocks.
struct BlockUpper {
  std::vector<int> offsets{0};       ///< DOF offset of each block, then the number of DOFs
  std::vector<int> column_starts{0};  ///< where each block column's stored blocks start, then their count
  std::vector<int> rows;             ///< the block row of each stored block
  std::vector<const double*> values;  ///< each stored block, column-major

  /// Number of blocks per side.
  int num_blocks() const { return int(offsets.size()) - 1; }
  /// Number of DOFs per side.
  int num_dofs() const { return offsets.back(); }
  /// The width of block b.
  int size(int b) const { return offsets[b + 1] - offsets[b]; }
  /// Scalar entries of the upper triangle the stored blocks cover (a diagonal block counts
  /// its upper triangle).
  long upper_nonzeros() const;
  /// The diagonal of H.
  Eigen::VectorXd diagonal() const;
  /// The upper triangle of H + shift·I as a compressed sparse column matrix, every entry of a
  /// stored block kept (zeros included), so that its pattern is the blocks'.
  Eigen::SparseMatrix<double> compressed(double shift = 0) const;
  /// y = (H + shift·I) x for the whole symmetric H, the shift added to the diagonal blocks'
  /// numbers first (so that it matches compressed(shift)'s product to the last bit). Blocks of
  /// y are summed in parallel, each in a fixed order: the result does not depend on the threads.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x, double shift = 0) const;
  /// multiply() with this pattern's block_rows() given, the same y bit for bit.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x, double shift, const BlockRows& by_row) const;
};

/// The stored off-diagonal blocks of H by block row.
BlockRows block_rows(const BlockUpper& H);

/// Whether `a` and `b` store the same blocks over the same DOF blocks (their numbers aside).
inline bool same_blocks(const BlockUpper& a, const BlockUpper& b) {
  return a.offsets == b.offsets && a.column_starts == b.column_starts && a.rows == b.rows;
}

/// Dense blocks copied out of a compressed upper triangle, and their view.
struct GatheredBlocks {
  GatheredBlocks() = default;
  GatheredBlocks(const GatheredBlocks&) = delete;  ///< the view would point into the original
  GatheredBlocks& operator=(const GatheredBlocks&) = delete;
  GatheredBlocks(GatheredBlocks&&) = default;  ///< the pool's storage moves with it
  GatheredBlocks& operator=(GatheredBlocks&&) = default;
  std::vector<double> pool;  ///< the blocks' numbers, in the view's order
  BlockUpper blocks;         ///< the view into `pool`
};

/// The blocks of `upper` (n × n CSC, entries with row ≤ column) over DOF blocks of the given
/// sizes (Σ sizes = n): a block is stored when any entry of `upper` falls in it, and entries
/// the CSC lacks are zero. Throws std::invalid_argument when the sizes do not add up to n or an
/// entry lies below the diagonal.
GatheredBlocks gather_blocks(const Eigen::SparseMatrix<double>& upper, const std::vector<int>& sizes);

}  // namespace stiffsoft
