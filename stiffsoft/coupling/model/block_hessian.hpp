#pragma once
/// @file The global Hessian over the DOF blocks of q (12 wide for an affine body, 3 for a soft
/// node), assembled in dense blocks (one per pair of blocks that interact) and turned into a
/// sparse matrix for the linear solver.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// Symmetric block-sparse matrix over variable-size DOF blocks; only blocks (i, j) with i ≤ j
/// are stored, each dense and column-major in one pool.
class BlockHessian {
 public:
  /// An empty matrix over the given DOF blocks (contiguous, in order).
  explicit BlockHessian(const std::vector<DofBlock>& blocks);
  /// Adds H (size_i × size_j) to block (i, j); for i > j the transpose is added to (j, i).
  void add(int i, int j, const Eigen::Ref<const Eigen::MatrixXd>& H);
  /// Zeroes every off-diagonal block in the row or column of a block with held[b] ≠ 0 (DOFs
  /// held on a prescribed motion): those blocks then decouple from the rest. The sparsity
  /// pattern stays as it was.
  void decouple(const std::vector<char>& held);
  /// The upper triangle as a compressed sparse column matrix (n × n, n = number of DOFs).
  Eigen::SparseMatrix<double> upper() const;
  /// The off-diagonal block pairs, sorted: equal lists mean equal sparsity patterns.
  std::vector<std::int64_t> pattern() const;
  /// y = H x for the full symmetric matrix.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;
  /// Number of blocks per side.
  int num_blocks() const { return int(m_blocks.size()); }

 private:
  using Block = Eigen::Map<Eigen::MatrixXd>;
  using ConstBlock = Eigen::Map<const Eigen::MatrixXd>;
  Block block_at(std::size_t at, int i, int j) {
    return Block(m_pool.data() + at, m_blocks[i].size, m_blocks[j].size);
  }
  ConstBlock block_at(std::size_t at, int i, int j) const {
    return ConstBlock(m_pool.data() + at, m_blocks[i].size, m_blocks[j].size);
  }

  std::vector<DofBlock> m_blocks;
  int m_num_dofs = 0;
  std::vector<double> m_pool;                                  // dense blocks, column-major
  std::vector<std::size_t> m_diagonal;                         // pool offset of block (i, i)
  std::unordered_map<std::int64_t, std::size_t> m_off_diagonal;  // key i * n + j, i < j → pool offset
};

}  // namespace stiffsoft
