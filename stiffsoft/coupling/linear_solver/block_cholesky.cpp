#include <stiffsoft/coupling/linear_solver/block_cholesky.hpp>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <Eigen/Cholesky>
#include <Eigen/OrderingMethods>
#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>

namespace stiffsoft {

namespace {

/// How the columns of one level of the elimination tree are split between threads: levels with
/// fewer than `minimum` columns run on the calling thread, larger ones in tasks of at least
/// `grain` columns. A task costs a few µs to hand out, a 12×12 column's factorisation about
/// 1 µs and its triangular solves about 0.1 µs.
struct LevelSplit {
  int minimum, grain;
};
constexpr LevelSplit kFactorSplit{32, 16};
constexpr LevelSplit kSolveSplit{1024, 512};

/// Calls f(j) for every column, level by level (children before parents when `upward`,
/// parents first otherwise); the columns of one level are independent.
template <class F>
void for_levels(const std::vector<int>& offsets, const std::vector<int>& columns, bool upward, LevelSplit split, F&& f) {
  const int levels = int(offsets.size()) - 1;
  for (int l = 0; l < levels; ++l) {
    const int level = upward ? l : levels - 1 - l;
    const int begin = offsets[level], end = offsets[level + 1];
    if (end - begin < split.minimum) {
      for (int k = begin; k < end; ++k) f(columns[k]);
      continue;
    }
    tbb::parallel_for(tbb::blocked_range<int>(begin, end, split.grain), [&](const tbb::blocked_range<int>& r) {
      for (int k = r.begin(); k < r.end(); ++k) f(columns[k]);
    });
  }
}

/// A rows × cols block of the pool, column-major; S fixes both sizes at compile time when every
/// DOF block has the same size (Eigen::Dynamic otherwise).
template <int S>
using Block = Eigen::Map<Eigen::Matrix<double, S, S>>;
template <int S>
using Segment = Eigen::Map<Eigen::Matrix<double, S, 1>>;

/// The graph of the DOF blocks: adjacent[I] holds every block J ≠ I that `upper` couples to I.
std::vector<std::vector<int>> block_graph(const Eigen::SparseMatrix<double>& upper, const std::vector<int>& offsets,
                                          const std::vector<int>& block_of) {
  const int nb = int(offsets.size()) - 1;
  std::vector<std::vector<int>> adjacent(nb);
  std::vector<int> mark(nb, -1);
  for (int J = 0; J < nb; ++J)
    for (int c = offsets[J]; c < offsets[J + 1]; ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(upper, c); it; ++it) {
        if (it.row() > c) throw std::invalid_argument("BlockCholesky: an entry below the diagonal");
        const int I = block_of[it.row()];
        if (I == J || mark[I] == J) continue;
        mark[I] = J;
        adjacent[I].push_back(J);
        adjacent[J].push_back(I);
      }
  return adjacent;
}

/// Approximate minimum degree (Eigen's AMD) on the block graph: order[k] is the block
/// eliminated k-th.
std::vector<int> minimum_degree_order(const std::vector<std::vector<int>>& adjacent) {
  const int nb = int(adjacent.size());
  std::vector<Eigen::Triplet<double>> edges;
  for (int I = 0; I < nb; ++I) {
    edges.emplace_back(I, I, 1.0);
    for (int J : adjacent[I]) edges.emplace_back(I, J, 1.0);
  }
  Eigen::SparseMatrix<double> graph(nb, nb);
  graph.setFromTriplets(edges.begin(), edges.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> ordering;
  Eigen::AMDOrdering<int>()(graph, ordering);
  return std::vector<int>(ordering.indices().data(), ordering.indices().data() + nb);
}

/// The block pattern of L in the elimination order and each column's height in the
/// elimination tree (0 for a leaf; a column's descendants all have smaller heights).
struct Elimination {
  std::vector<std::vector<int>> structure;  ///< struct(j): the block rows below j, ascending
  std::vector<int> height;
};

/// struct(j) = the later neighbours of j ∪ the structs of j's children minus j, and
/// parent(j) = min struct(j).
Elimination eliminate(const std::vector<std::vector<int>>& adjacent, const std::vector<int>& order,
                      const std::vector<int>& position) {
  const int nb = int(order.size());
  Elimination e{std::vector<std::vector<int>>(nb), std::vector<int>(nb, 0)};
  std::vector<std::vector<int>> children(nb);
  for (int j = 0; j < nb; ++j) {
    std::vector<int>& s = e.structure[j];
    for (int I : adjacent[order[j]])
      if (position[I] > j) s.push_back(position[I]);
    for (int c : children[j]) {
      for (int i : e.structure[c])
        if (i != j) s.push_back(i);
      e.height[j] = std::max(e.height[j], e.height[c] + 1);
    }
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
    if (!s.empty()) children[s.front()].push_back(j);
  }
  return e;
}

}  // namespace

void BlockCholesky::analyze(const Eigen::SparseMatrix<double>& upper, const std::vector<int>& sizes) {
  const int n = int(upper.rows());
  std::vector<int> offsets{0};
  for (int s : sizes) offsets.push_back(offsets.back() + s);
  if (upper.cols() != n || offsets.back() != n)
    throw std::invalid_argument("BlockCholesky: DOF blocks of " + std::to_string(offsets.back()) +
                                " DOFs for a " + std::to_string(n) + " × " + std::to_string(upper.cols()) + " matrix");
  const int nb = int(sizes.size());
  std::vector<int> block_of(n);
  for (int b = 0; b < nb; ++b) std::fill(block_of.begin() + offsets[b], block_of.begin() + offsets[b + 1], b);
  const std::vector<std::vector<int>> adjacent = block_graph(upper, offsets, block_of);
  const std::vector<int> order = minimum_degree_order(adjacent);
  std::vector<int> position(nb);
  for (int k = 0; k < nb; ++k) position[order[k]] = k;
  const auto [structure, height] = eliminate(adjacent, order, position);

  m_columns.resize(nb);
  m_column_offsets.assign(nb + 1, 0);
  m_entries.clear();
  std::size_t pool = 0;
  m_flops = m_nonzeros = 0;
  for (int j = 0; j < nb; ++j) {
    const int b = order[j], s = sizes[b];
    m_columns[j] = {s, offsets[b], pool};
    pool += std::size_t(s) * s;
    m_nonzeros += 0.5 * s * (s + 1);
    m_flops += s * double(s) * s / 3;
    for (int i : structure[j]) {
      const int si = sizes[order[i]];
      m_entries.push_back({i, pool});
      pool += std::size_t(si) * s;
      m_nonzeros += double(si) * s;
      m_flops += double(si) * s * s;
    }
    m_column_offsets[j + 1] = int(m_entries.size());
  }
  m_pool.assign(pool, 0.0);

  // Which earlier columns update column j: k with j ∈ struct(k), in ascending k.
  m_update_offsets.assign(nb + 1, 0);
  for (int k = 0; k < nb; ++k)
    for (int i : structure[k]) ++m_update_offsets[i + 1];
  for (int j = 0; j < nb; ++j) m_update_offsets[j + 1] += m_update_offsets[j];
  m_updates.resize(m_update_offsets[nb]);
  std::vector<int> fill(m_update_offsets.begin(), m_update_offsets.end() - 1);
  for (int k = 0; k < nb; ++k) {
    const double sk = m_columns[k].size;
    for (int p = 0; p < int(structure[k].size()); ++p) {
      const int j = structure[k][p];
      m_updates[fill[j]++] = {k, p};
      const double sj = m_columns[j].size;
      m_flops += sj * sj * sk;
      for (int q = p + 1; q < int(structure[k].size()); ++q) m_flops += 2 * m_columns[structure[k][q]].size * sj * sk;
    }
  }

  // Columns by height: a column's descendants all have smaller heights.
  const int levels = nb ? 1 + *std::max_element(height.begin(), height.end()) : 0;
  m_level_offsets.assign(levels + 1, 0);
  for (int j = 0; j < nb; ++j) ++m_level_offsets[height[j] + 1];
  for (int l = 0; l < levels; ++l) m_level_offsets[l + 1] += m_level_offsets[l];
  m_by_level.resize(nb);
  std::vector<int> next(m_level_offsets.begin(), m_level_offsets.end() - 1);
  for (int j = 0; j < nb; ++j) m_by_level[next[height[j]]++] = j;

  // Where each stored entry of `upper` goes: the lower triangle of a diagonal block, or the
  // block of L below the diagonal that holds it (transposed when its block row comes first).
  // A column's entries run through its blocks in order, so each block is looked up once.
  m_target.resize(upper.nonZeros());
  m_target_column.resize(upper.nonZeros());
  m_input.clear();
  m_outer.assign(upper.outerIndexPtr(), upper.outerIndexPtr() + n + 1);
  m_inner.assign(upper.innerIndexPtr(), upper.innerIndexPtr() + upper.nonZeros());
  std::int64_t k = 0;
  const auto entry_at = [&](int row, int column) {
    const auto begin = m_entries.begin() + m_column_offsets[column], end = m_entries.begin() + m_column_offsets[column + 1];
    return std::lower_bound(begin, end, row, [](const Entry& e, int r) { return e.row < r; })->at;
  };
  for (int c = 0; c < n; ++c) {
    const int J = block_of[c], cl = c - offsets[J], pj = position[J];
    int I = -1;
    std::int64_t base = 0, row_stride = 0, column_stride = 0;  // target = base + rl·row_stride + cl·column_stride
    for (Eigen::SparseMatrix<double>::InnerIterator it(upper, c); it; ++it, ++k) {
      if (block_of[it.row()] != I) {
        I = block_of[it.row()];
        const int pi = position[I];
        if (pi > pj) {
          base = std::int64_t(entry_at(pi, pj)), row_stride = 1, column_stride = sizes[I];
        } else if (pi < pj) {
          base = std::int64_t(entry_at(pj, pi)), row_stride = sizes[J], column_stride = 1;
        } else {
          base = std::int64_t(m_columns[pj].diagonal), row_stride = sizes[J], column_stride = 1;
        }
      }
      const int rl = int(it.row()) - offsets[I];
      // Diagonal blocks: entry (rl ≤ cl) goes to the lower triangle, (cl, rl).
      m_target[k] = base + rl * row_stride + cl * column_stride;
      m_target_column[k] = std::min(position[I], pj);
    }
  }
  const bool uniform = std::all_of(sizes.begin(), sizes.end(), [&](int s) { return s == sizes.front(); });
  m_uniform = uniform && nb ? sizes.front() : 0;
}

template <int S>
bool BlockCholesky::factor_column(int j, std::vector<int>& slot) {
  const Column& cj = m_columns[j];
  const int s = cj.size;
  double* pool = m_pool.data();
  Block<S> D(pool + cj.diagonal, s, s);
  const int begin = m_column_offsets[j], end = m_column_offsets[j + 1];
  for (int e = begin; e < end; ++e) slot[m_entries[e].row] = e;
  // Left-looking: subtract L_ik L_jkᵀ of every earlier column k whose struct holds j.
  for (int u = m_update_offsets[j]; u < m_update_offsets[j + 1]; ++u) {
    const auto [k, p] = m_updates[u];
    const int sk = m_columns[k].size, first = m_column_offsets[k];
    const Block<S> Ljk(pool + m_entries[first + p].at, s, sk);
    D -= Ljk.lazyProduct(Ljk.transpose());
    for (int q = first + p + 1; q < m_column_offsets[k + 1]; ++q) {
      const Entry& e = m_entries[q];
      const int si = m_columns[e.row].size;
      Block<S>(pool + m_entries[slot[e.row]].at, si, s) -= Block<S>(pool + e.at, si, sk).lazyProduct(Ljk.transpose());
    }
  }
  // D's lower triangle holds the updated pivot block; the pool keeps L_jj⁻¹ in its place, so
  // that the blocks below and both triangular solves are plain products.
  const Eigen::LLT<Eigen::Matrix<double, S, S>> llt(D);
  if (llt.info() != Eigen::Success) return false;
  D.setIdentity(s, s);
  llt.matrixL().solveInPlace(D);
  for (int e = begin; e < end; ++e) {
    Block<S> B(pool + m_entries[e].at, m_columns[m_entries[e].row].size, s);
    B = Eigen::Matrix<double, S, S>(B.lazyProduct(D.transpose()));  // L_ij = B_i L_jj⁻ᵀ
  }
  return true;
}

bool BlockCholesky::factorize(const Eigen::SparseMatrix<double>& upper) {
  if (!analysed()) throw std::logic_error("BlockCholesky::factorize before analyze");
  const double* values = upper.valuePtr();
  const std::size_t nnz = m_target.size(), nb = m_columns.size();
  // After a successful factorisation of the same pattern only the columns whose entries changed
  // and the columns they update (their ancestors) are computed again: the others' blocks of L
  // are those a full factorisation would give, bit for bit (friction's revised directions
  // change a few stencils' blocks and factorise again).
  std::vector<char> redo(nb, 1);
  if (m_input.size() == nnz) {
    std::fill(redo.begin(), redo.end(), 0);
    for (std::size_t k = 0; k < nnz; ++k)
      if (values[k] != m_input[k]) redo[m_target_column[k]] = 1;
    for (int j : m_by_level)  // a column's descendants come before it
      for (int u = m_update_offsets[j]; u < m_update_offsets[j + 1] && !redo[j]; ++u) redo[j] = redo[m_updates[u].column];
  }
  m_refactored = 0;
  for (std::size_t j = 0; j < nb; ++j) {
    if (!redo[j]) continue;
    ++m_refactored;
    const std::size_t end = j + 1 < nb ? m_columns[j + 1].diagonal : m_pool.size();
    std::fill(m_pool.begin() + m_columns[j].diagonal, m_pool.begin() + end, 0.0);
  }
  for (std::size_t k = 0; k < nnz; ++k)
    if (redo[m_target_column[k]]) m_pool[m_target[k]] = values[k];
  tbb::enumerable_thread_specific<std::vector<int>> slots(std::vector<int>(nb, -1));
  std::atomic<bool> ok{true};
  for_levels(m_level_offsets, m_by_level, true, kFactorSplit, [&](int j) {
    if (!redo[j] || !ok.load(std::memory_order_relaxed)) return;
    const bool column_ok = m_uniform == 12 ? factor_column<12>(j, slots.local())
                           : m_uniform == 3 ? factor_column<3>(j, slots.local())
                                            : factor_column<Eigen::Dynamic>(j, slots.local());
    if (!column_ok) ok = false;
  });
  if (ok)
    m_input.assign(values, values + nnz);
  else
    m_input.clear();  // the factor is incomplete: the next factorisation starts afresh
  return ok;
}

template <int S>
void BlockCholesky::solve_in_place(Eigen::VectorXd& x) const {
  const double* pool = m_pool.data();
  const auto L = [&](std::size_t at, int rows, int cols) { return Eigen::Map<const Eigen::Matrix<double, S, S>>(pool + at, rows, cols); };
  // L y = b, children first: y_j = L_jj⁻¹ (b_j − Σ_k L_jk y_k).
  for_levels(m_level_offsets, m_by_level, true, kSolveSplit, [&](int j) {
    const Column& cj = m_columns[j];
    Segment<S> y(x.data() + cj.offset, cj.size);
    for (int u = m_update_offsets[j]; u < m_update_offsets[j + 1]; ++u) {
      const auto [k, p] = m_updates[u];
      const Column& ck = m_columns[k];
      y -= L(m_entries[m_column_offsets[k] + p].at, cj.size, ck.size).lazyProduct(Segment<S>(x.data() + ck.offset, ck.size));
    }
    y = Eigen::Matrix<double, S, 1>(L(cj.diagonal, cj.size, cj.size).lazyProduct(y));  // L_jj⁻¹: zero above its diagonal
  });
  // Lᵀ x = y, parents first: x_j = L_jj⁻ᵀ (y_j − Σ_i L_ijᵀ x_i).
  for_levels(m_level_offsets, m_by_level, false, kSolveSplit, [&](int j) {
    const Column& cj = m_columns[j];
    Segment<S> y(x.data() + cj.offset, cj.size);
    for (int e = m_column_offsets[j]; e < m_column_offsets[j + 1]; ++e) {
      const Column& ci = m_columns[m_entries[e].row];
      y -= L(m_entries[e].at, ci.size, cj.size).transpose().lazyProduct(Segment<S>(x.data() + ci.offset, ci.size));
    }
    y = Eigen::Matrix<double, S, 1>(L(cj.diagonal, cj.size, cj.size).transpose().lazyProduct(y));
  });
}

Eigen::VectorXd BlockCholesky::solve(const Eigen::VectorXd& b) const {
  Eigen::VectorXd x = b;
  if (m_uniform == 12)
    solve_in_place<12>(x);
  else if (m_uniform == 3)
    solve_in_place<3>(x);
  else
    solve_in_place<Eigen::Dynamic>(x);
  return x;
}

}  // namespace stiffsoft
