#include <stiffsoft/coupling/model/block_hessian.hpp>

#include <algorithm>

namespace stiffsoft {

BlockHessian::BlockHessian(const std::vector<DofBlock>& blocks) : m_blocks(blocks) {
  m_diagonal.reserve(blocks.size());
  std::size_t at = 0;
  for (const DofBlock& b : blocks) {
    m_diagonal.push_back(at);
    at += std::size_t(b.size) * b.size;
    m_num_dofs = b.offset + b.size;
  }
  m_pool.assign(at, 0.0);
}

void BlockHessian::add(int i, int j, const Eigen::Ref<const Eigen::MatrixXd>& H) {
  if (i == j) {
    block_at(m_diagonal[i], i, i) += H;
    return;
  }
  const std::int64_t n = num_blocks();
  const bool upper = i < j;
  const std::int64_t key = upper ? i * n + j : j * n + i;
  const int r = upper ? i : j, c = upper ? j : i;
  auto [it, fresh] = m_off_diagonal.try_emplace(key, m_pool.size());
  if (fresh) m_pool.resize(m_pool.size() + std::size_t(m_blocks[r].size) * m_blocks[c].size, 0.0);
  if (upper)
    block_at(it->second, r, c) += H;
  else
    block_at(it->second, r, c) += H.transpose();
}

void BlockHessian::decouple(const std::vector<char>& held) {
  const std::int64_t n = num_blocks();
  for (const auto& [key, at] : m_off_diagonal) {
    const int i = int(key / n), j = int(key % n);
    if (held[i] || held[j]) block_at(at, i, j).setZero();
  }
}

std::vector<std::int64_t> BlockHessian::pattern() const {
  std::vector<std::int64_t> keys;
  keys.reserve(m_off_diagonal.size());
  for (const auto& [key, at] : m_off_diagonal) keys.push_back(key);
  std::sort(keys.begin(), keys.end());
  return keys;
}

Eigen::SparseMatrix<double> BlockHessian::upper() const {
  const std::int64_t n = num_blocks();
  // Column-wise block lists so the matrix is filled in order, without triplet sorting.
  std::vector<std::vector<std::pair<int, std::size_t>>> column_blocks(n);
  for (const auto& [key, at] : m_off_diagonal) column_blocks[key % n].push_back({int(key / n), at});
  for (auto& c : column_blocks) std::sort(c.begin(), c.end());
  Eigen::SparseMatrix<double> H(m_num_dofs, m_num_dofs);
  Eigen::VectorXi nnz(m_num_dofs);
  for (int bj = 0; bj < n; ++bj) {
    int above = 0;
    for (const auto& [bi, at] : column_blocks[bj]) above += m_blocks[bi].size;
    for (int c = 0; c < m_blocks[bj].size; ++c) nnz[m_blocks[bj].offset + c] = above + c + 1;
  }
  H.reserve(nnz);
  for (int bj = 0; bj < n; ++bj) {
    const DofBlock& col_block = m_blocks[bj];
    const ConstBlock diagonal = block_at(m_diagonal[bj], bj, bj);
    for (int c = 0; c < col_block.size; ++c) {
      const int col = col_block.offset + c;
      for (const auto& [bi, at] : column_blocks[bj]) {
        const ConstBlock block = block_at(at, bi, bj);
        for (int r = 0; r < m_blocks[bi].size; ++r) H.insert(m_blocks[bi].offset + r, col) = block(r, c);
      }
      for (int r = 0; r <= c; ++r) H.insert(col_block.offset + r, col) = diagonal(r, c);
    }
  }
  H.makeCompressed();
  return H;
}

Eigen::VectorXd BlockHessian::multiply(const Eigen::VectorXd& x) const {
  const std::int64_t n = num_blocks();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(x.size());
  for (int b = 0; b < n; ++b) {
    const DofBlock& d = m_blocks[b];
    y.segment(d.offset, d.size) += block_at(m_diagonal[b], b, b) * x.segment(d.offset, d.size);
  }
  for (const auto& [key, at] : m_off_diagonal) {
    const int i = int(key / n), j = int(key % n);
    const DofBlock &bi = m_blocks[i], &bj = m_blocks[j];
    const ConstBlock block = block_at(at, i, j);
    y.segment(bi.offset, bi.size) += block * x.segment(bj.offset, bj.size);
    y.segment(bj.offset, bj.size) += block.transpose() * x.segment(bi.offset, bi.size);
  }
  return y;
}

}  // namespace stiffsoft
