#include <stiffsoft/coupling/linear_solver/block_sparse_pattern.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace stiffsoft {

namespace {

/// Position of block column J in the block row whose columns are [begin, end), or −1.
std::int64_t find_block(const std::vector<int>& columns, int begin, int end, int J) {
  const auto first = columns.begin() + begin, last = columns.begin() + end;
  const auto it = std::lower_bound(first, last, J);
  return (it != last && *it == J) ? std::int64_t(it - columns.begin()) : -1;
}

}  // namespace

BlockSparsePattern::BlockSparsePattern(const Eigen::SparseMatrix<double>& upper, BlockStorage storage,
                                       int row_begin, int row_end)
    : m_storage(storage) {
  const int n = int(upper.rows());
  if (upper.cols() != n || n % 3 != 0)
    throw std::invalid_argument("BlockSparsePattern: the matrix is " + std::to_string(upper.rows()) + " × " +
                                std::to_string(upper.cols()) + "; expected square with a multiple of 3 rows");
  if (!upper.isCompressed())
    throw std::invalid_argument("BlockSparsePattern: the matrix must be compressed (makeCompressed())");
  m_num_block_rows = n / 3;
  m_row_begin = row_begin;
  m_row_end = row_end < 0 ? m_num_block_rows : row_end;
  if (m_row_begin < 0 || m_row_begin > m_row_end || m_row_end > m_num_block_rows)
    throw std::invalid_argument("BlockSparsePattern: block rows [" + std::to_string(row_begin) + ", " +
                                std::to_string(row_end) + ") outside [0, " +
                                std::to_string(m_num_block_rows) + ")");
  const int* outer = upper.outerIndexPtr();
  const int* inner = upper.innerIndexPtr();
  m_outer.assign(outer, outer + n + 1);
  m_inner.assign(inner, inner + upper.nonZeros());
  auto owned = [&](int I) { return I >= m_row_begin && I < m_row_end; };

  // Block columns of each owned block row. Scalar columns of one block column J are
  // consecutive, so `seen[I] == J` deduplicates the 9 scalars of block (I, J).
  const int local = m_row_end - m_row_begin;
  std::vector<std::vector<int>> rows(local);
  std::vector<int> seen(m_num_block_rows, -1);
  for (int c = 0; c < n; ++c) {
    const int J = c / 3;
    for (int k = outer[c]; k < outer[c + 1]; ++k) {
      const int r = inner[k];
      if (r > c)
        throw std::invalid_argument("BlockSparsePattern: entry (" + std::to_string(r) + ", " +
                                    std::to_string(c) +
                                    ") lies below the diagonal; expected the upper triangle only");
      const int I = r / 3;
      if (seen[I] == J) continue;
      seen[I] = J;
      if (owned(I)) rows[I - m_row_begin].push_back(J);
      if (storage == BlockStorage::Full && I != J && owned(J)) rows[J - m_row_begin].push_back(I);
    }
  }
  m_row_offsets.assign(local + 1, 0);
  for (int i = 0; i < local; ++i) {
    std::sort(rows[i].begin(), rows[i].end());
    m_row_offsets[i + 1] = m_row_offsets[i] + int(rows[i].size());
  }
  m_block_columns.reserve(m_row_offsets[local]);
  for (const std::vector<int>& r : rows) m_block_columns.insert(m_block_columns.end(), r.begin(), r.end());

  // Where each scalar goes: entry (r, c) at element (r mod 3, c mod 3) of block (I, J), its
  // mirror (c, r) at element (c mod 3, r mod 3) of block (J, I); blocks are column-major.
  const std::int64_t nnz = upper.nonZeros();
  m_target.assign(nnz, -1);
  m_mirror.assign(nnz, -1);
  auto position = [&](int I, int J) {
    const int i = I - m_row_begin;
    return find_block(m_block_columns, m_row_offsets[i], m_row_offsets[i + 1], J);
  };
  for (int c = 0; c < n; ++c) {
    const int J = c / 3;
    // A column's rows ascend, so the (up to three) scalars of one block come in a run: each
    // block's positions are looked up once per run.
    int run = -1;
    std::int64_t at = -1, mirror_at = -1;
    for (int k = outer[c]; k < outer[c + 1]; ++k) {
      const int r = inner[k];
      const int I = r / 3;
      if (I != run) {
        run = I;
        at = owned(I) ? position(I, J) : -1;
        mirror_at = storage == BlockStorage::Full && I != J && owned(J) ? position(J, I) : -1;
      }
      if (at >= 0) m_target[k] = 9 * at + 3 * (c % 3) + r % 3;
      if (r == c) continue;
      if (I == J) {
        if (at >= 0) m_mirror[k] = 9 * at + 3 * (r % 3) + c % 3;
      } else if (mirror_at >= 0) {
        m_mirror[k] = 9 * mirror_at + 3 * (r % 3) + c % 3;
      }
    }
  }
}

void BlockSparsePattern::gather_values(const Eigen::SparseMatrix<double>& upper,
                                       std::vector<double>& values) const {
  if (!same_pattern(upper))
    throw std::invalid_argument(
        "BlockSparsePattern::gather_values: the matrix's pattern differs from the analysed one");
  values.assign(num_values(), 0.0);
  const double* v = upper.valuePtr();
  const std::int64_t nnz = upper.nonZeros();
  // In parallel: every stored value has one source.
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, nnz, 4096), [&](const tbb::blocked_range<std::int64_t>& r) {
    for (std::int64_t k = r.begin(); k < r.end(); ++k) {
      if (m_target[k] >= 0) values[m_target[k]] = v[k];
      if (m_mirror[k] >= 0) values[m_mirror[k]] = v[k];
    }
  });
}

std::int64_t BlockSparsePattern::pieces_at(int I, int J, int count) const {
  const int i = I - m_row_begin;
  const std::int64_t at = find_block(m_block_columns, m_row_offsets[i], m_row_offsets[i + 1], J);
  // Blocks (I, J) … (I, J + count − 1) are consecutive: the row's columns ascend.
  if (at < 0 || at + count > m_row_offsets[i + 1] || m_block_columns[std::size_t(at + count - 1)] != J + count - 1)
    throw std::invalid_argument("BlockSparsePattern: blocks (" + std::to_string(I) + ", " + std::to_string(J) +
                                ") to (" + std::to_string(I) + ", " + std::to_string(J + count - 1) +
                                ") are not in the analysed pattern");
  return 9 * at;
}

void BlockSparsePattern::map_blocks(const BlockUpper& H) {
  if (H.num_dofs() != 3 * m_num_block_rows)
    throw std::invalid_argument("BlockSparsePattern::map_blocks: " + std::to_string(H.num_dofs()) +
                                " DOFs; the analysed pattern has " + std::to_string(3 * m_num_block_rows));
  // Built aside and kept only when complete: after a throw the last mapping stands.
  std::vector<int> starts(H.rows.size() + 1, 0), mirror_starts(H.rows.size() + 1, 0);
  std::vector<std::int64_t> rows, mirrors;
  for (int j = 0; j < H.num_blocks(); ++j)
    for (int k = H.column_starts[j]; k < H.column_starts[j + 1]; ++k) {
      const int i = H.rows[k], nq = H.size(j) / 3;
      starts[std::size_t(k)] = int(rows.size());
      mirror_starts[std::size_t(k)] = int(mirrors.size());
      for (int p = 0; p < H.size(i) / 3; ++p) {
        const int I = H.offsets[i] / 3 + p, q_begin = i == j ? p : 0;
        const bool owned = I >= m_row_begin && I < m_row_end;
        rows.push_back(owned ? pieces_at(I, H.offsets[j] / 3 + q_begin, nq - q_begin) : -1);
        if (m_storage != BlockStorage::Full) continue;
        for (int q = q_begin + (i == j ? 1 : 0); q < nq; ++q) {  // the mirrors (J, I) of the off-diagonal pieces
          const int J = H.offsets[j] / 3 + q;
          mirrors.push_back(J >= m_row_begin && J < m_row_end ? pieces_at(J, I, 1) : -1);
        }
      }
    }
  starts.back() = int(rows.size());
  mirror_starts.back() = int(mirrors.size());
  m_piece_row_starts = std::move(starts);
  m_piece_rows = std::move(rows);
  m_piece_mirror_starts = std::move(mirror_starts);
  m_piece_mirrors = std::move(mirrors);
  m_mapped = BlockUpper{H.offsets, H.column_starts, H.rows, {}};
}

void BlockSparsePattern::gather_values(const BlockUpper& H, double shift, double* values) const {
  if (!maps(H)) throw std::logic_error("BlockSparsePattern::gather_values: H's blocks were not mapped (map_blocks())");
  // Each stored block of H in 3×3 pieces (p, q), a diagonal block's on or above its diagonal,
  // by rows of pieces. Block columns in parallel: every stored value has one source.
  tbb::parallel_for(tbb::blocked_range<int>(0, H.num_blocks(), 16), [&](const tbb::blocked_range<int>& range) {
    for (int j = range.begin(); j < range.end(); ++j)
      for (int k = H.column_starts[j]; k < H.column_starts[j + 1]; ++k) {
        const int i = H.rows[k], si = H.size(i), nq = H.size(j) / 3;
        const double* block = H.values[k];
        const std::int64_t* mirror = m_piece_mirrors.data() + m_piece_mirror_starts[std::size_t(k)];
        for (int p = 0; p < si / 3; ++p) {
          const int q_begin = i == j ? p : 0;
          const auto entry = [&](int q, int r, int c) { return block[3 * p + r + std::size_t(3 * q + c) * si]; };
          const std::int64_t at = m_piece_rows[std::size_t(m_piece_row_starts[std::size_t(k)] + p)];
          if (at >= 0) {
            double* out = values + at;
            for (int q = q_begin; q < nq; ++q, out += 9) {
              if (i == j && q == p) {  // a diagonal piece: its upper triangle, mirrored, the shift on the diagonal
                for (int c = 0; c < 3; ++c) {
                  for (int r = 0; r < c; ++r) out[3 * c + r] = out[3 * r + c] = entry(q, r, c);
                  out[4 * c] = entry(q, c, c) + shift;
                }
                continue;
              }
              for (int c = 0; c < 3; ++c)
                for (int r = 0; r < 3; ++r) out[3 * c + r] = entry(q, r, c);
            }
          }
          if (m_storage != BlockStorage::Full) continue;
          for (int q = q_begin + (i == j ? 1 : 0); q < nq; ++q, ++mirror) {  // the mirrors (J, I) of the off-diagonal pieces
            if (*mirror < 0) continue;
            double* out = values + *mirror;
            for (int c = 0; c < 3; ++c)
              for (int r = 0; r < 3; ++r) out[3 * r + c] = entry(q, r, c);
          }
        }
      }
  });
}

Eigen::SparseMatrix<double> BlockSparsePattern::upper(const double* values) const {
  if (m_row_begin != 0 || m_row_end != m_num_block_rows)
    throw std::logic_error("BlockSparsePattern::upper: this pattern holds block rows [" +
                           std::to_string(m_row_begin) + ", " + std::to_string(m_row_end) + ") of " +
                           std::to_string(m_num_block_rows) + ", not all");
  const int n = int(m_outer.size()) - 1;
  Eigen::SparseMatrix<double> H(n, n);
  H.resizeNonZeros(Eigen::Index(m_inner.size()));
  std::copy(m_outer.begin(), m_outer.end(), H.outerIndexPtr());
  std::copy(m_inner.begin(), m_inner.end(), H.innerIndexPtr());
  for (std::size_t k = 0; k < m_inner.size(); ++k) H.valuePtr()[k] = values[std::size_t(m_target[k])];
  return H;
}

bool BlockSparsePattern::same_pattern(const Eigen::SparseMatrix<double>& upper) const {
  if (!upper.isCompressed() || upper.rows() + 1 != std::int64_t(m_outer.size()) ||
      upper.nonZeros() != std::int64_t(m_inner.size()))
    return false;
  return std::equal(m_outer.begin(), m_outer.end(), upper.outerIndexPtr()) &&
         std::equal(m_inner.begin(), m_inner.end(), upper.innerIndexPtr());
}

void BlockSparsePattern::count_blocks(int column_begin, int column_end, std::vector<int>& diagonal,
                                      std::vector<int>& off_diagonal) const {
  const int local = m_row_end - m_row_begin;
  diagonal.assign(local, 0);
  off_diagonal.assign(local, 0);
  for (int i = 0; i < local; ++i)
    for (int k = m_row_offsets[i]; k < m_row_offsets[i + 1]; ++k) {
      const int J = m_block_columns[k];
      (J >= column_begin && J < column_end ? diagonal : off_diagonal)[i] += 1;
    }
}

std::vector<int> infer_block_sizes(const Eigen::SparseMatrix<double>& upper) {
  const BlockSparsePattern pattern(upper, BlockStorage::Upper);
  const std::vector<int>& offsets = pattern.row_offsets();
  const std::vector<int>& columns = pattern.block_columns();
  auto present = [&](int I, int J) { return find_block(columns, offsets[I], offsets[I + 1], J) >= 0; };
  const int nb = pattern.num_block_rows();
  std::vector<int> sizes;
  for (int I = 0; I < nb;) {
    bool dense = I + 3 < nb;
    for (int a = 0; dense && a < 3; ++a)
      for (int b = a + 1; dense && b < 4; ++b) dense = present(I + a, I + b);
    sizes.push_back(dense ? 12 : 3);
    I += dense ? 4 : 1;
  }
  return sizes;
}

std::vector<int> split_rows(const std::vector<int>& block_sizes, int parts) {
  if (parts < 1)
    throw std::invalid_argument("split_rows: parts = " + std::to_string(parts) + "; expected ≥ 1");
  const std::int64_t n = std::accumulate(block_sizes.begin(), block_sizes.end(), std::int64_t(0));
  std::vector<int> bounds{0};
  std::int64_t row = 0;
  std::size_t b = 0;
  for (int p = 1; p < parts; ++p) {
    const std::int64_t target = n * p / parts;
    // Take blocks while that brings the boundary closer to the target.
    while (b < block_sizes.size() && std::abs(row + block_sizes[b] - target) <= std::abs(row - target))
      row += block_sizes[b++];
    bounds.push_back(int(row));
  }
  bounds.push_back(int(n));
  return bounds;
}

}  // namespace stiffsoft
