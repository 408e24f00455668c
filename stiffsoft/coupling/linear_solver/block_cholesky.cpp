#include <stiffsoft/coupling/linear_solver/block_cholesky.hpp>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for_each.h>

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>

#include <stiffsoft/coupling/for_each_item.hpp>
#include <stiffsoft/coupling/linear_solver/column_strips.hpp>

namespace stiffsoft {

namespace {

/// Blocks per task of the comparisons and copies around the factorisation: a 12×12 block's
/// copy costs about 50 ns, so a task of 32 blocks outweighs its hand-out.
constexpr std::size_t kCopyGrain = 32;

/// A factorisation of fewer columns than this runs on the calling thread: a 12×12 column's
/// factorisation costs about 1 µs, handing one out a few µs.
constexpr std::size_t kSerialColumns = 32;

/// Calls f(j) for every column j of `todo` once the columns of `todo` it waits on are done:
/// waits_on(j, g) calls g(k) for every column k that j waits on, released_by(k, g) calls g(j)
/// for every column j that waits on k. `todo` lists each column after those it waits on, and
/// with one thread (or few columns) that is the order. Otherwise a column runs as soon as its
/// last dependency is done, on the thread that finished it (the first it releases) or handed to
/// another (the rest): no barrier between levels of the dependency graph, whose narrow levels
/// (the top of an elimination tree) hold a third of a pile's factorisation (docs/benchmarks.md,
/// session 54). f must read only the columns j waits on and write only its own.
template <class WaitsOn, class ReleasedBy, class F>
void for_each_when_ready(const std::vector<int>& todo, int columns, WaitsOn&& waits_on, ReleasedBy&& released_by,
                         F&& f) {
  if (todo.size() < kSerialColumns || available_threads() == 1) {
    for (int j : todo) f(j);
    return;
  }
  std::vector<char> member(std::size_t(columns), 0);
  for (int j : todo) member[std::size_t(j)] = 1;
  const std::unique_ptr<std::atomic<int>[]> pending(new std::atomic<int>[std::size_t(columns)]);
  std::vector<int> ready;
  for (int j : todo) {
    int count = 0;
    waits_on(j, [&](int k) { count += member[std::size_t(k)]; });
    pending[std::size_t(j)].store(count, std::memory_order_relaxed);
    if (count == 0) ready.push_back(j);
  }
  tbb::parallel_for_each(ready.begin(), ready.end(), [&](int first, tbb::feeder<int>& feeder) {
    for (int j = first; j >= 0;) {
      f(j);
      int next = -1;
      released_by(j, [&](int d) {
        // acq_rel: the last release sees every write of the columns d waits on.
        if (!member[std::size_t(d)] || pending[std::size_t(d)].fetch_sub(1, std::memory_order_acq_rel) != 1) return;
        if (next < 0)
          next = d;
        else
          feeder.add(d);
      });
      j = next;
    }
  });
}

/// A rows × cols block of the pool, column-major; S fixes both sizes at compile time when every
/// DOF block has the same size (Eigen::Dynamic otherwise).
template <int S>
using Block = Eigen::Map<Eigen::Matrix<double, S, S>>;
template <int S>
using Segment = Eigen::Map<Eigen::Matrix<double, S, 1>>;

/// D −= L Lᵀ on and below D's diagonal (what the pivot's factorisation reads). At 12 × 12, by
/// strips of four columns from the diagonal down: 96 of the 144 entries.
template <int S>
void subtract_lower_gram(Block<S>& D, const Block<S>& L) {
  if constexpr (S == 12) {
    for_column_strips([&]<int C>() {
      D.template block<12 - 4 * C, 4>(4 * C, 4 * C) -=
          L.template middleRows<12 - 4 * C>(4 * C).lazyProduct(L.template middleRows<4>(4 * C).transpose());
    });
  } else {
    D -= L.lazyProduct(L.transpose());
  }
}

/// B ← B Xᵀ for a lower-triangular X (B is si × s). At 12 × 12, each strip of four columns of
/// the result reads only the columns of B that X's rows reach: 96 of the 144 products.
template <int S>
void multiply_by_lower_transpose(Block<S>& B, const Block<S>& X) {
  if constexpr (S == 12) {
    Eigen::Matrix<double, 12, 12> result;
    for_column_strips([&]<int C>() {
      result.template middleCols<4>(4 * C) =
          B.template leftCols<4 * C + 4>().lazyProduct(X.template block<4, 4 * C + 4>(4 * C, 0).transpose());
    });
    B = result;
  } else {
    B = Eigen::Matrix<double, S, S>(B.lazyProduct(X.transpose()));
  }
}

/// The graph of the DOF blocks: adjacent[I] holds every block J ≠ I that H couples to I.
std::vector<std::vector<int>> block_graph(const BlockUpper& H) {
  std::vector<std::vector<int>> adjacent(H.num_blocks());
  for (int J = 0; J < H.num_blocks(); ++J)
    for (int k = H.column_starts[J]; k < H.column_starts[J + 1]; ++k) {
      const int I = H.rows[k];
      if (I > J) throw std::invalid_argument("BlockCholesky: a block below the diagonal");
      if (I == J) continue;
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

/// struct(j), the block rows below j in column j of L (ascending), of the exact factor:
/// the later neighbours of j ∪ the structs of j's children minus j, where parent(j) = min struct(j).
std::vector<std::vector<int>> eliminate(const std::vector<std::vector<int>>& adjacent, const std::vector<int>& order,
                                        const std::vector<int>& position) {
  const int nb = int(order.size());
  std::vector<std::vector<int>> structure(nb), children(nb);
  for (int j = 0; j < nb; ++j) {
    std::vector<int>& s = structure[j];
    for (int I : adjacent[order[j]])
      if (position[I] > j) s.push_back(position[I]);
    for (int c : children[j])
      for (int i : structure[c])
        if (i != j) s.push_back(i);
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
    if (!s.empty()) children[s.front()].push_back(j);
  }
  return structure;
}

/// struct(j) of IC(0) in the blocks' own order: the later neighbours of j, ascending.
std::vector<std::vector<int>> later_neighbours(std::vector<std::vector<int>> adjacent) {
  for (int j = 0; j < int(adjacent.size()); ++j) {
    std::vector<int>& s = adjacent[j];
    s.erase(std::remove_if(s.begin(), s.end(), [&](int i) { return i < j; }), s.end());
    std::sort(s.begin(), s.end());
  }
  return adjacent;
}

/// D ← L⁻¹ in place, L the lower Cholesky factor of the s × s block whose lower triangle D
/// holds (D = L Lᵀ); false when a pivot is not positive (D is then not positive definite).
/// Plain loops: for blocks of 12 or 3 the compiler unrolls them, where Eigen's LLT and
/// triangular solve go through its general blocked kernels.
template <int S>
bool invert_cholesky_factor(Block<S>& D, int size) {
  const int s = S == Eigen::Dynamic ? size : S;  // a constant bound the compiler can unroll
  for (int j = 0; j < s; ++j) {  // L, column by column, over D's lower triangle
    double pivot = D(j, j);
    for (int k = 0; k < j; ++k) pivot -= D(j, k) * D(j, k);
    if (!(pivot > 0.0)) return false;
    const double l_jj = std::sqrt(pivot);
    D(j, j) = l_jj;
    for (int i = j + 1; i < s; ++i) {
      double v = D(i, j);
      for (int k = 0; k < j; ++k) v -= D(i, k) * D(j, k);
      D(i, j) = v / l_jj;
    }
  }
  // L⁻¹ by rows: row i of X = L⁻¹ needs only rows k < i of X and row i of L, so it overwrites
  // row i of L once L's row is read.
  for (int i = 0; i < s; ++i) {
    const double inverse_ii = 1.0 / D(i, i);
    for (int j = 0; j < i; ++j) {
      double v = 0.0;
      for (int k = j; k < i; ++k) v += D(i, k) * D(k, j);
      D(i, j) = -v * inverse_ii;
    }
    D(i, i) = inverse_ii;
    for (int j = i + 1; j < s; ++j) D(i, j) = 0.0;
  }
  return true;
}

}  // namespace

void BlockCholesky::analyze(const Eigen::SparseMatrix<double>& upper, const std::vector<int>& sizes) {
  m_gathered = gather_blocks(upper, sizes);
  analyze(m_gathered.blocks);
}

void BlockCholesky::analyze(const BlockUpper& H) {
  // The pattern analysed last (a new time step's first Hessian, often) keeps its analysis.
  if (analysed() && same_blocks(H, m_factorised)) return;
  const int nb = H.num_blocks();
  std::vector<int> sizes(nb);
  for (int b = 0; b < nb; ++b) sizes[b] = H.size(b);
  const std::vector<std::vector<int>> adjacent = block_graph(H);
  std::vector<int> order(nb);
  std::iota(order.begin(), order.end(), 0);
  if (m_fill == Fill::Complete) order = minimum_degree_order(adjacent);
  std::vector<int> position(nb);
  for (int k = 0; k < nb; ++k) position[order[k]] = k;
  const std::vector<std::vector<int>> structure =
      m_fill == Fill::Complete ? eliminate(adjacent, order, position) : later_neighbours(adjacent);

  m_columns.resize(nb);
  m_column_offsets.assign(nb + 1, 0);
  m_entries.clear();
  std::size_t pool = 0;
  m_flops = m_nonzeros = 0;
  for (int j = 0; j < nb; ++j) {
    const int b = order[j], s = sizes[b];
    m_columns[j] = {s, H.offsets[b], pool};
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
  // Not zeroed: a factorisation after an analysis loads every column (load_column: H's blocks
  // copied, the rest zeroed) and the inversion zeroes each L_jj's upper triangle, so no old
  // number is read. Zeroing it was 1 % of an iteration of full's landing on two threads.
  m_pool.resize(pool);

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
      for (int q = p + 1; q < int(structure[k].size()); ++q)
        if (m_fill == Fill::Complete ||  // IC(0) drops the pairs that would fill
            std::binary_search(structure[j].begin(), structure[j].end(), structure[k][q]))
          m_flops += 2 * m_columns[structure[k][q]].size * sj * sk;
    }
  }

  // Where each stored block of H goes, and where its numbers are kept between factorisations;
  // which blocks of L no block of H fills.
  std::vector<char> filled_diagonal(nb, 0), filled_entry(m_entries.size(), 0);
  const auto entry_at = [&](int row, int column) {
    const auto begin = m_entries.begin() + m_column_offsets[column], end = m_entries.begin() + m_column_offsets[column + 1];
    const auto e = std::lower_bound(begin, end, row, [](const Entry& e, int r) { return e.row < r; });
    filled_entry[std::size_t(e - m_entries.begin())] = 1;
    return e->at;
  };
  m_target.clear();
  m_input_at.clear();
  std::size_t input = 0;
  for (int J = 0; J < nb; ++J)
    for (int k = H.column_starts[J]; k < H.column_starts[J + 1]; ++k) {
      const int I = H.rows[k], pi = position[I], pj = position[J];
      if (pi == pj) {
        m_target.push_back({Target::Diagonal, pj, m_columns[pj].diagonal, J});
        filled_diagonal[pj] = 1;
      } else if (pi > pj) {
        m_target.push_back({Target::AsIs, pj, entry_at(pi, pj), J});
      } else {
        m_target.push_back({Target::Transposed, pi, entry_at(pj, pi), J});
      }
      m_input_at.push_back(input);
      input += std::size_t(sizes[I]) * sizes[J];
    }
  m_input_at.push_back(input);
  m_input.resize(input);  // read only once a complete factorisation has copied every block into it
  m_input_offsets.assign(nb + 1, 0);
  for (const Target& t : m_target) ++m_input_offsets[t.column + 1];
  for (int j = 0; j < nb; ++j) m_input_offsets[j + 1] += m_input_offsets[j];
  m_inputs.resize(m_target.size());
  std::vector<int> next_input(m_input_offsets.begin(), m_input_offsets.end() - 1);
  for (std::size_t k = 0; k < m_target.size(); ++k) m_inputs[next_input[m_target[k].column]++] = int(k);
  m_unfilled_offsets.assign(1, 0);
  m_unfilled.clear();
  for (int j = 0; j < nb; ++j) {
    const std::size_t s = m_columns[j].size;
    if (!filled_diagonal[j]) m_unfilled.push_back({m_columns[j].diagonal, s * s});
    for (int e = m_column_offsets[j]; e < m_column_offsets[j + 1]; ++e)
      if (!filled_entry[e]) m_unfilled.push_back({m_entries[e].at, std::size_t(m_columns[m_entries[e].row].size) * s});
    m_unfilled_offsets.push_back(int(m_unfilled.size()));
  }
  m_factorised = BlockUpper{H.offsets, H.column_starts, H.rows, {}};
  for (std::size_t k = 0; k + 1 < m_input_at.size(); ++k) m_factorised.values.push_back(m_input.data() + m_input_at[k]);
  m_factorised_rows = block_rows(m_factorised);
  m_kept = false;
  const bool uniform = std::all_of(sizes.begin(), sizes.end(), [&](int s) { return s == sizes.front(); });
  m_uniform = uniform && nb ? sizes.front() : 0;
}

void BlockCholesky::load_column(int j, const BlockUpper& H, double shift, double boost) {
  // L_jj's upper triangle keeps what the last factorisation left there: nothing uses it before
  // the inversion sets it to zero.
  for (int u = m_unfilled_offsets[j]; u < m_unfilled_offsets[j + 1]; ++u)
    std::fill_n(m_pool.begin() + m_unfilled[u].at, m_unfilled[u].count, 0.0);
  for (int input = m_input_offsets[j]; input < m_input_offsets[j + 1]; ++input) {
    const int k = m_inputs[input];
    const Target& t = m_target[k];
    const int si = H.size(H.rows[k]), sj = H.size(t.block_column);
    const double* a = H.values[k];  // a(r, c) = a[r + c·si]
    double* l = m_pool.data() + t.at;
    if (t.kind == Target::AsIs) {
      std::copy(a, a + std::size_t(si) * sj, l);
    } else if (t.kind == Target::Transposed) {
      for (int c = 0; c < sj; ++c)
        for (int r = 0; r < si; ++r) l[c + std::size_t(r) * sj] = a[r + std::size_t(c) * si];
    } else {
      for (int c = 0; c < sj; ++c)
        for (int r = 0; r <= c; ++r) l[c + std::size_t(r) * sj] = a[r + std::size_t(c) * si];
      for (int c = 0; c < sj; ++c) l[c + std::size_t(c) * sj] = l[c + std::size_t(c) * sj] * (1 + boost) + shift;
    }
  }
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
    subtract_lower_gram<S>(D, Ljk);
    for (int q = first + p + 1; q < m_column_offsets[k + 1]; ++q) {
      const Entry& e = m_entries[q];
      if (slot[e.row] < 0) continue;  // IC(0) drops the fill
      const int si = m_columns[e.row].size;
      Block<S>(pool + m_entries[slot[e.row]].at, si, s) -= Block<S>(pool + e.at, si, sk).lazyProduct(Ljk.transpose());
    }
  }
  for (int e = begin; e < end; ++e) slot[m_entries[e].row] = -1;
  // D's lower triangle holds the updated pivot block; the pool keeps L_jj⁻¹ in its place, so
  // that the blocks below and both triangular solves are plain products.
  if (!invert_cholesky_factor<S>(D, s)) return false;
  for (int e = begin; e < end; ++e) {
    Block<S> B(pool + m_entries[e].at, m_columns[m_entries[e].row].size, s);
    multiply_by_lower_transpose<S>(B, D);  // L_ij = B_i L_jj⁻ᵀ
  }
  return true;
}

bool BlockCholesky::factorize(const Eigen::SparseMatrix<double>& upper, double boost) {
  if (!analysed()) throw std::logic_error("BlockCholesky::factorize before analyze");
  std::vector<int> sizes(m_factorised.num_blocks());
  for (int b = 0; b < m_factorised.num_blocks(); ++b) sizes[b] = m_factorised.size(b);
  m_gathered = gather_blocks(upper, sizes);
  return factorize(m_gathered.blocks, 0, boost);
}

bool BlockCholesky::factorize(const BlockUpper& H, double shift, double boost) {
  if (!analysed()) throw std::logic_error("BlockCholesky::factorize before analyze");
  if (!same_blocks(H, m_factorised))
    throw std::invalid_argument("BlockCholesky::factorize: not the block pattern analyze() was given");
  const std::size_t blocks = m_target.size(), nb = m_columns.size();
  const auto numbers = [&](std::size_t k) { return m_input_at[k + 1] - m_input_at[k]; };
  // After a successful factorisation of the same pattern, shift and boost only the columns whose
  // blocks changed and the columns they update (in turn) are computed again: the
  // others' blocks of L are those a full factorisation would give, bit for bit (friction's
  // revised directions change a few stencils' blocks and factorise again).
  std::vector<char> redo(nb, 1);
  if (m_kept && shift == m_shift && boost == m_boost) {
    std::vector<char> changed(blocks);
    for_each_item(blocks, kCopyGrain, [&](std::size_t k) {
      changed[k] = !std::equal(H.values[k], H.values[k] + numbers(k), m_input.data() + m_input_at[k]);
    });
    std::fill(redo.begin(), redo.end(), 0);
    for (std::size_t k = 0; k < blocks; ++k)
      if (changed[k]) redo[m_target[k].column] = 1;
    for (int j = 0; j < int(nb); ++j)  // the columns that update a column come before it
      for (int u = m_update_offsets[j]; u < m_update_offsets[j + 1] && !redo[j]; ++u) redo[j] = redo[m_updates[u].column];
  }
  m_refactored = std::size_t(std::count(redo.begin(), redo.end(), 1));
  tbb::enumerable_thread_specific<std::vector<int>> slots(std::vector<int>(nb, -1));
  std::atomic<bool> ok{true};
  std::vector<int> todo;  // in ascending order: each column after those that update it
  for (int j = 0; j < int(nb); ++j)
    if (redo[j]) todo.push_back(j);
  const auto updaters = [&](int j, auto&& g) {  // the columns k that update j (j ∈ struct(k))
    for (int u = m_update_offsets[j]; u < m_update_offsets[j + 1]; ++u) g(m_updates[u].column);
  };
  const auto updated = [&](int k, auto&& g) {  // the columns k updates: struct(k)
    for (int e = m_column_offsets[k]; e < m_column_offsets[k + 1]; ++e) g(m_entries[e].row);
  };
  for_each_when_ready(todo, int(nb), updaters, updated, [&](int j) {
    if (!ok.load(std::memory_order_relaxed)) return;
    load_column(j, H, shift, boost);
    const bool column_ok = m_uniform == 12 ? factor_column<12>(j, slots.local())
                           : m_uniform == 3 ? factor_column<3>(j, slots.local())
                                            : factor_column<Eigen::Dynamic>(j, slots.local());
    if (!column_ok) ok = false;
  });
  // H is kept only under a complete factor: after a failure the next factorisation starts afresh.
  m_kept = ok;
  if (ok) {
    // A column not computed again had every block equal to the kept one: only the others are copied.
    for_each_item(blocks, kCopyGrain, [&](std::size_t k) {
      if (redo[m_target[k].column]) std::copy(H.values[k], H.values[k] + numbers(k), m_input.data() + m_input_at[k]);
    });
    m_shift = shift;
    m_boost = boost;
  }
  return ok;
}

template <int S>
void BlockCholesky::solve_in_place(Eigen::VectorXd& x) const {
  const double* pool = m_pool.data();
  const auto L = [&](std::size_t at, int rows, int cols) { return Eigen::Map<const Eigen::Matrix<double, S, S>>(pool + at, rows, cols); };
  const int nb = int(m_columns.size());
  // L y = b, children first: y_j = L_jj⁻¹ (b_j − Σ_k L_jk y_k).
  for (int j = 0; j < nb; ++j) {
    const Column& cj = m_columns[j];
    Segment<S> y(x.data() + cj.offset, cj.size);
    for (int u = m_update_offsets[j]; u < m_update_offsets[j + 1]; ++u) {
      const auto [k, p] = m_updates[u];
      const Column& ck = m_columns[k];
      y -= L(m_entries[m_column_offsets[k] + p].at, cj.size, ck.size).lazyProduct(Segment<S>(x.data() + ck.offset, ck.size));
    }
    y = Eigen::Matrix<double, S, 1>(L(cj.diagonal, cj.size, cj.size).lazyProduct(y));  // L_jj⁻¹: zero above its diagonal
  }
  // Lᵀ x = y, parents first: x_j = L_jj⁻ᵀ (y_j − Σ_i L_ijᵀ x_i).
  for (int j = nb - 1; j >= 0; --j) {
    const Column& cj = m_columns[j];
    Segment<S> y(x.data() + cj.offset, cj.size);
    for (int e = m_column_offsets[j]; e < m_column_offsets[j + 1]; ++e) {
      const Column& ci = m_columns[m_entries[e].row];
      y -= L(m_entries[e].at, ci.size, cj.size).transpose().lazyProduct(Segment<S>(x.data() + ci.offset, ci.size));
    }
    y = Eigen::Matrix<double, S, 1>(L(cj.diagonal, cj.size, cj.size).transpose().lazyProduct(y));
  }
}

Eigen::VectorXd BlockCholesky::multiply(const Eigen::VectorXd& x) const {
  if (!m_kept) throw std::logic_error("BlockCholesky::multiply without a factor");
  return m_factorised.multiply(x, m_shift, m_factorised_rows);
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
