#include <stiffsoft/coupling/model/block_hessian.hpp>

#include <algorithm>

#include <stiffsoft/coupling/linear_solver/column_strips.hpp>

namespace stiffsoft {

BlockHessian::BlockHessian(const std::vector<DofBlock>& blocks) : m_blocks(blocks), m_row_slots(blocks.size()) {
  m_diagonal.reserve(blocks.size());
  std::size_t at = 0;
  for (const DofBlock& b : blocks) {
    m_diagonal.push_back(at);
    at += std::size_t(b.size) * b.size;
    m_num_dofs = b.offset + b.size;
  }
  m_diagonal_size = at;
  m_pool.assign(at, 0.0);
}

void BlockHessian::clear() {
  m_previous_version = pattern_version();
  m_previous_live = m_live.n;
  m_live.n = 0;
  m_grown.n = 0;
  // Bodies that parted long ago leave their blocks' storage behind: once it outgrows the last
  // matrix's, only that matrix's blocks keep storage.
  constexpr std::size_t kSpareBlocks = 4096;
  if (m_slots.size() > 2 * m_previous_live + kSpareBlocks) keep_only_live_slots();
  ++m_generation;
  // Diagonal blocks are always part of the matrix; off-diagonal ones are zeroed on their first
  // touch in the new assembly (live_slot), so untouched storage costs nothing.
  std::fill(m_pool.begin(), m_pool.begin() + std::ptrdiff_t(m_diagonal_size), 0.0);
}

void BlockHessian::keep_only_live_slots() {
  std::vector<Slot> kept;
  kept.reserve(m_previous_live);
  std::size_t at = m_diagonal_size;
  for (std::vector<RowEntry>& row : m_row_slots) {
    std::vector<RowEntry> kept_row;
    for (const RowEntry& e : row) {
      const Slot& s = m_slots[std::size_t(e.slot)];
      if (!live(s)) continue;
      kept_row.push_back({e.column, int(kept.size())});
      kept.push_back({s.row, s.column, at, s.generation});
      at += std::size_t(m_blocks[s.row].size) * m_blocks[s.column].size;
    }
    row.swap(kept_row);
  }
  // The kept blocks' values need not move: each is zeroed at its first touch after clear().
  m_slots.swap(kept);
  std::vector<double> pool(m_pool.begin(), m_pool.begin() + std::ptrdiff_t(m_diagonal_size));
  pool.resize(at, 0.0);
  m_pool.swap(pool);
}

BlockHessian::Slot* BlockHessian::stored_slot(int row, int column) {
  for (const RowEntry& e : m_row_slots[row]) {
    if (e.column != column) continue;
    Slot& s = m_slots[e.slot];
    if (!live(s)) {
      if (s.generation + 1 != m_generation) m_grown.raise();
      s.generation = m_generation;
      block_at(s.at, row, column).setZero();
      m_live.raise();
    }
    return &s;
  }
  return nullptr;
}

bool BlockHessian::stored(int i, int j) const {
  const std::vector<RowEntry>& row = m_row_slots[i];
  return std::any_of(row.begin(), row.end(), [&](const RowEntry& e) { return e.column == j; });
}

BlockHessian::Slot& BlockHessian::live_slot(int row, int column) {
  if (Slot* s = stored_slot(row, column)) return *s;
  m_row_slots[row].push_back({column, int(m_slots.size())});
  m_slots.push_back({row, column, m_pool.size(), m_generation});
  m_pool.resize(m_pool.size() + std::size_t(m_blocks[row].size) * m_blocks[column].size, 0.0);
  m_grown.raise();
  m_live.raise();
  return m_slots.back();
}

void BlockHessian::add(int i, int j, const Eigen::Ref<const Eigen::MatrixXd>& H) {
  if (m_blocks[i].size == 3 && m_blocks[j].size == 3) {  // two soft nodes: fixed-size code
    const Eigen::Map<const Eigen::Matrix3d, 0, Eigen::OuterStride<>> h(H.data(), Eigen::OuterStride<>(H.outerStride()));
    // The slot first: creating it may move the pool.
    const std::size_t at = i == j ? m_diagonal[i] : live_slot(std::min(i, j), std::max(i, j)).at;
    if (i <= j)
      Eigen::Map<Eigen::Matrix3d>(m_pool.data() + at) += h;
    else
      Eigen::Map<Eigen::Matrix3d>(m_pool.data() + at) += h.transpose();
    return;
  }
  if (i == j) {
    block_at(m_diagonal[i], i, i) += H;
    return;
  }
  if (i < j)
    block_at(live_slot(i, j).at, i, j) += H;
  else
    block_at(live_slot(j, i).at, j, i) += H.transpose();
}

void BlockHessian::add_upper(int i, int j, const double* values) {
  if (i == j && m_blocks[i].size == 12) {  // an affine body's: by strips of four columns down to the diagonal
    double* D = m_pool.data() + m_diagonal[i];
    for_column_strips([&]<int C>() {
      using Strip = Eigen::Matrix<double, 4 * C + 4, 4>;
      Eigen::Map<Strip, 0, Eigen::OuterStride<12>>(D + 48 * C) += Eigen::Map<const Strip, 0, Eigen::OuterStride<12>>(values + 48 * C);
    });
    return;
  }
  if (i == j) {
    block_at(m_diagonal[i], i, i).triangularView<Eigen::Upper>() += ConstBlock(values, m_blocks[i].size, m_blocks[i].size);
    return;
  }
  add_off_diagonal(live_slot(i, j).at, i, j, values);  // the slot first: creating it may move the pool
}

bool BlockHessian::add_upper_stored(int i, int j, const double* values) {
  if (i == j) {
    add_upper(i, j, values);
    return true;
  }
  const Slot* s = stored_slot(i, j);
  if (s) add_off_diagonal(s->at, i, j, values);
  return s != nullptr;
}

void BlockHessian::add_off_diagonal(std::size_t at, int i, int j, const double* values) {
  if (m_blocks[i].size == 12 && m_blocks[j].size == 12) {  // two affine bodies: fixed-size code
    Eigen::Map<Eigen::Matrix<double, 12, 12>>(m_pool.data() + at) += Eigen::Map<const Eigen::Matrix<double, 12, 12>>(values);
    return;
  }
  block_at(at, i, j) += ConstBlock(values, m_blocks[i].size, m_blocks[j].size);
}

void BlockHessian::decouple(const std::vector<char>& held) {
  for (const Slot& s : m_slots)
    if (live(s) && (held[s.row] || held[s.column])) block_at(s.at, s.row, s.column).setZero();
}

std::uint64_t BlockHessian::pattern_version() const {
  // Within an assembly slots only ever join the pattern, so a pattern that is not the previous
  // one is fixed by the assembly's number and its count of live slots.
  if (m_grown.n == 0 && m_live.n == m_previous_live) return m_previous_version;
  return (m_generation << 32) | m_live.n;
}

std::vector<std::int64_t> BlockHessian::pattern() const {
  const std::int64_t n = num_blocks();
  std::vector<std::int64_t> keys;
  keys.reserve(m_live.n);
  for (const Slot& s : m_slots)
    if (live(s)) keys.push_back(s.row * n + s.column);
  std::sort(keys.begin(), keys.end());
  return keys;
}

BlockHessian::ColumnSlots BlockHessian::column_slots() const {
  ColumnSlots out;
  out.offsets.assign(m_blocks.size() + 1, 0);
  for (const Slot& s : m_slots)
    if (live(s)) ++out.offsets[s.column + 1];
  for (std::size_t j = 0; j < m_blocks.size(); ++j) out.offsets[j + 1] += out.offsets[j];
  out.slots.resize(std::size_t(out.offsets.back()));
  std::vector<int> next(out.offsets.begin(), out.offsets.end() - 1);
  // Rows in ascending order, so each column's slots come out sorted by row.
  for (const std::vector<RowEntry>& row : m_row_slots)
    for (const RowEntry& e : row)
      if (live(m_slots[e.slot])) out.slots[std::size_t(next[e.column]++)] = e.slot;
  return out;
}

BlockUpper BlockHessian::upper_blocks() const {
  const int n = num_blocks();
  const ColumnSlots columns = column_slots();
  BlockUpper H;
  H.offsets.reserve(std::size_t(n) + 1);
  H.column_starts.reserve(std::size_t(n) + 1);
  H.rows.reserve(columns.slots.size() + std::size_t(n));
  H.values.reserve(columns.slots.size() + std::size_t(n));
  for (int j = 0; j < n; ++j) {
    H.offsets.push_back(m_blocks[j].offset + m_blocks[j].size);
    for (int k = columns.offsets[j]; k < columns.offsets[j + 1]; ++k) {
      const Slot& slot = m_slots[columns.slots[k]];
      H.rows.push_back(slot.row);
      H.values.push_back(m_pool.data() + slot.at);
    }
    H.rows.push_back(j);  // the diagonal block, below the column's others
    H.values.push_back(m_pool.data() + m_diagonal[j]);
    H.column_starts.push_back(int(H.rows.size()));
  }
  return H;
}

Eigen::SparseMatrix<double> BlockHessian::upper() const { return upper_blocks().compressed(); }

Eigen::VectorXd BlockHessian::multiply(const Eigen::VectorXd& x) const {
  const int n = num_blocks();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(x.size());
  for (int b = 0; b < n; ++b) {
    const DofBlock& d = m_blocks[b];
    y.segment(d.offset, d.size) += block_at(m_diagonal[b], b, b).selfadjointView<Eigen::Upper>() * x.segment(d.offset, d.size);
  }
  for (const Slot& s : m_slots) {
    if (!live(s)) continue;
    const DofBlock &bi = m_blocks[s.row], &bj = m_blocks[s.column];
    const ConstBlock block = block_at(s.at, s.row, s.column);
    y.segment(bi.offset, bi.size) += block * x.segment(bj.offset, bj.size);
    y.segment(bj.offset, bj.size) += block.transpose() * x.segment(bi.offset, bi.size);
  }
  return y;
}

}  // namespace stiffsoft
