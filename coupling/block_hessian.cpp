#include "coupling/block_hessian.hpp"

#include <algorithm>

namespace stiffsoft {

BlockHessian::BlockHessian(int num_blocks) : m_diagonal(num_blocks, abd::Matrix12d::Zero()) {}

void BlockHessian::add(int i, int j, const abd::Matrix12d& H) {
  if (i == j) {
    m_diagonal[i] += H;
    return;
  }
  const std::int64_t n = num_blocks();
  if (i < j) {
    auto [it, fresh] = m_off_diagonal.try_emplace(i * n + j, H);
    if (!fresh) it->second += H;
  } else {
    auto [it, fresh] = m_off_diagonal.try_emplace(j * n + i, H.transpose());
    if (!fresh) it->second += H.transpose();
  }
}

std::vector<std::int64_t> BlockHessian::pattern() const {
  std::vector<std::int64_t> keys;
  keys.reserve(m_off_diagonal.size());
  for (const auto& [key, block] : m_off_diagonal) keys.push_back(key);
  std::sort(keys.begin(), keys.end());
  return keys;
}

Eigen::SparseMatrix<double> BlockHessian::upper() const {
  const std::int64_t n = num_blocks();
  // Column-wise block lists so the matrix is filled in order, without triplet sorting.
  std::vector<std::vector<std::pair<int, const abd::Matrix12d*>>> column_blocks(n);
  for (const auto& [key, block] : m_off_diagonal) column_blocks[key % n].push_back({int(key / n), &block});
  for (auto& c : column_blocks) std::sort(c.begin(), c.end());
  Eigen::SparseMatrix<double> H(12 * n, 12 * n);
  Eigen::VectorXi nnz(12 * n);
  for (int bj = 0; bj < n; ++bj)
    for (int c = 0; c < 12; ++c) nnz[12 * bj + c] = 12 * int(column_blocks[bj].size()) + c + 1;
  H.reserve(nnz);
  for (int bj = 0; bj < n; ++bj)
    for (int c = 0; c < 12; ++c) {
      const int col = 12 * bj + c;
      for (const auto& [bi, block] : column_blocks[bj])
        for (int r = 0; r < 12; ++r) H.insert(12 * bi + r, col) = (*block)(r, c);
      for (int r = 0; r <= c; ++r) H.insert(12 * bj + r, col) = m_diagonal[bj](r, c);
    }
  H.makeCompressed();
  return H;
}

Eigen::VectorXd BlockHessian::multiply(const Eigen::VectorXd& x) const {
  const std::int64_t n = num_blocks();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(x.size());
  for (int b = 0; b < n; ++b) y.segment<12>(12 * b) += m_diagonal[b] * x.segment<12>(12 * b);
  for (const auto& [key, block] : m_off_diagonal) {
    const int i = int(key / n), j = int(key % n);
    y.segment<12>(12 * i) += block * x.segment<12>(12 * j);
    y.segment<12>(12 * j) += block.transpose() * x.segment<12>(12 * i);
  }
  return y;
}

}  // namespace stiffsoft
