#pragma once
/// @file The 3×3-block (BSR) layout of an upper-triangular scalar CSC matrix, as PETSc's BAIJ
/// and SBAIJ formats with block size 3 store it, and the map that copies values into it
/// without searching. Pure Eigen; the PETSc backend builds on it.

#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

#include <stiffsoft/coupling/linear_solver/block_upper.hpp>

namespace stiffsoft {

/// Which 3×3 blocks a block row stores.
enum class BlockStorage {
  Upper,  ///< blocks (I, J) with J ≥ I (PETSc SBAIJ); diagonal blocks full (both triangles)
  Full    ///< every block (I, J) of the symmetric matrix (PETSc BAIJ)
};

/// The 3×3 blocks of H = upper + upperᵀ − diag(upper), in compressed block rows, restricted to
/// the block rows [row_begin, row_end) that one MPI rank owns (all of them when serial).
/// A block is present when any scalar entry of `upper` falls in it (or in its mirror);
/// entries the CSC does not store are zeros.
class BlockSparsePattern {
 public:
  /// Analyses `upper` (n × n CSC, n a multiple of 3, only entries with row ≤ column);
  /// throws std::invalid_argument otherwise. Block rows [row_begin, row_end) (units of 3
  /// rows); row_end = −1 means all.
  BlockSparsePattern(const Eigen::SparseMatrix<double>& upper, BlockStorage storage, int row_begin = 0,
                     int row_end = -1);
  /// Number of block rows (= block columns) of the whole matrix, n / 3.
  int num_block_rows() const { return m_num_block_rows; }
  /// First owned block row.
  int row_begin() const { return m_row_begin; }
  /// One past the last owned block row.
  int row_end() const { return m_row_end; }
  /// Offsets into block_columns() per owned block row, size (row_end − row_begin) + 1.
  const std::vector<int>& row_offsets() const { return m_row_offsets; }
  /// Global block-column index of each stored block, ascending within a block row.
  const std::vector<int>& block_columns() const { return m_block_columns; }
  /// Number of stored values: 9 per block, each block column-major, blocks in row order.
  std::size_t num_values() const { return 9 * m_block_columns.size(); }
  /// The storage this pattern was built for.
  BlockStorage storage() const { return m_storage; }
  /// Copies the values of `upper` (same pattern as analysed) into `values` (resized to
  /// num_values(); entries the CSC lacks are zero), mirroring what the storage needs.
  void gather_values(const Eigen::SparseMatrix<double>& upper, std::vector<double>& values) const;
  /// Prepares gather_values(H, shift, values) for matrices stored in the blocks of H (their
  /// numbers aside), whose compressed pattern must be the analysed one (every DOF block a
  /// multiple of 3 wide): where each row of 3×3 pieces of each stored block goes. Throws
  /// std::invalid_argument for a block of H the pattern lacks.
  void map_blocks(const BlockUpper& H);
  /// Whether H stores the blocks of the last map_blocks().
  bool maps(const BlockUpper& H) const { return same_blocks(H, m_mapped); }
  /// The values gather_values(H.compressed(shift), values) copies, read from H's blocks into
  /// the num_values() numbers at `values` without forming the compressed matrix (every one is
  /// written). Throws std::logic_error unless maps(H).
  void gather_values(const BlockUpper& H, double shift, double* values) const;
  /// The analysed upper triangle with the numbers gather_values() would have read from it
  /// (the inverse of either gather_values()); throws std::logic_error unless this
  /// pattern holds every row.
  Eigen::SparseMatrix<double> upper(const double* values) const;
  /// True when `upper` has exactly the scalar pattern this was built from.
  bool same_pattern(const Eigen::SparseMatrix<double>& upper) const;
  /// Blocks per owned block row whose column lies in [column_begin, column_end) (`diagonal`)
  /// and outside it (`off_diagonal`), for PETSc's preallocation (MPI column ownership).
  void count_blocks(int column_begin, int column_end, std::vector<int>& diagonal,
                    std::vector<int>& off_diagonal) const;

 private:
  /// The value index of block (I, J) of owned row I, checking that (I, J + 1) … (I, J + count − 1)
  /// follow it; throws std::invalid_argument when they are not all in the pattern.
  std::int64_t pieces_at(int I, int J, int count) const;

  BlockStorage m_storage;
  int m_num_block_rows = 0, m_row_begin = 0, m_row_end = 0;
  std::vector<int> m_row_offsets, m_block_columns;
  std::vector<std::int64_t> m_target, m_mirror;  // per scalar nonzero: value index, −1 when not owned/none
  std::vector<int> m_outer, m_inner;             // the analysed scalar pattern
  // map_blocks(): per stored block of H, where its rows of pieces start in m_piece_rows, and
  // for each such row the value index of its first piece (−1: not owned)
  std::vector<int> m_piece_row_starts;
  std::vector<std::int64_t> m_piece_rows;
  // …and, with Full storage, per stored block where the value indices of its off-diagonal
  // pieces' mirrors start in m_piece_mirrors (in the order gather_values() visits them; −1: not owned)
  std::vector<int> m_piece_mirror_starts;
  std::vector<std::int64_t> m_piece_mirrors;
  BlockUpper m_mapped;  // the blocks mapped (no values)
};

/// The DOF blocks of `upper` when the caller gave none: scanning 3-blocks in order, four
/// consecutive ones whose six mutual blocks are all present form one 12-block (an affine
/// body's dense 12×12 diagonal block), otherwise a 3-block stands alone. Only a guess for
/// preconditioning (four nodes of one tet numbered consecutively also pass as a 12-block,
/// which is harmless for block Jacobi).
std::vector<int> infer_block_sizes(const Eigen::SparseMatrix<double>& upper);

/// Row boundaries that split consecutive DOF blocks into `parts` contiguous ranges of nearly
/// equal row counts without cutting a block: size parts + 1, first 0, last Σ sizes.
std::vector<int> split_rows(const std::vector<int>& block_sizes, int parts);

}  // namespace stiffsoft
