#include <stiffsoft/coupling/linear_solver/block_upper.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace stiffsoft {

namespace {

/// One stored block's product into the block of y that `target` names: y_i += A x_j for the
/// block's row i, y_j += Aᵀ x_i for its column j, or, for a diagonal block, y_j += A x_j over its
/// upper triangle with `shift` added to its diagonal first. S fixes both sizes at compile time
/// when they are equal and known (Eigen::Dynamic otherwise).
enum class Part { Row, Column };

/// y += A x for a 12×12 block A (column-major at `a`): each row's sum from zero over the columns
/// in order, then added to y, the order of Eigen's column-major matrix–vector kernel
/// (GeneralMatrixVector.h), whose calls for the off-diagonal blocks cost 7 % of full's second
/// second at 1/240 (docs/benchmarks.md, session 54); the same numbers bit for bit, in a loop the
/// compiler unrolls.
inline void add_product(const double* a, const double* x, double* y) {
  Eigen::Matrix<double, 12, 1> sum = Eigen::Matrix<double, 12, 1>::Zero();
  for (int j = 0; j < 12; ++j) sum += Eigen::Map<const Eigen::Matrix<double, 12, 1>>(a + 12 * j) * x[j];
  Eigen::Map<Eigen::Matrix<double, 12, 1>>(y) += sum;
}

/// y += Aᵀ x for a 12×12 block A (column-major at `a`): each column's dot product with x as
/// Eigen's row-major kernel forms it with two-double packets (the even and the odd terms summed
/// apart, in order, then added), then added to y; the same numbers bit for bit.
inline void add_transposed_product(const double* a, const double* x, double* y) {
  using Pair = Eigen::Array2d;  // (even term, odd term): one two-double packet
  for (int i = 0; i < 12; ++i) {
    const double* column = a + 12 * i;
    Pair sum = Pair::Zero();
    for (int j = 0; j < 12; j += 2) sum += Eigen::Map<const Pair>(column + j) * Eigen::Map<const Pair>(x + j);
    y[i] += sum[0] + sum[1];
  }
}

template <int S>
void multiply_block(const double* values, int i, int j, Part target, const BlockUpper& H, double shift,
                    const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const int si = H.size(i), sj = H.size(j);
  const Eigen::Map<const Eigen::Matrix<double, S, S>> A(values, si, sj);
  auto xi = x.segment<S>(H.offsets[i], si), xj = x.segment<S>(H.offsets[j], sj);
  if (i == j && shift != 0) {
    Eigen::Matrix<double, S, S> D = A;
    D.diagonal().array() += shift;
    y.segment<S>(H.offsets[j], sj).noalias() += D.template selfadjointView<Eigen::Upper>() * xj;
  } else if (i == j) {
    y.segment<S>(H.offsets[j], sj).noalias() += A.template selfadjointView<Eigen::Upper>() * xj;
  } else if constexpr (S == 12) {
    if (target == Part::Row)
      add_product(values, &x[H.offsets[j]], &y[H.offsets[i]]);
    else
      add_transposed_product(values, &x[H.offsets[i]], &y[H.offsets[j]]);
  } else if (target == Part::Row) {
    y.segment<S>(H.offsets[i], si).noalias() += A * xj;
  } else {
    y.segment<S>(H.offsets[j], sj).noalias() += A.transpose() * xi;
  }
}

}  // namespace

long BlockUpper::upper_nonzeros() const {
  long count = 0;
  for (int j = 0; j < num_blocks(); ++j)
    for (int k = column_starts[j]; k < column_starts[j + 1]; ++k)
      count += rows[k] == j ? long(size(j)) * (size(j) + 1) / 2 : long(size(rows[k])) * size(j);
  return count;
}

Eigen::VectorXd BlockUpper::diagonal() const {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(num_dofs());
  for (int j = 0; j < num_blocks(); ++j)
    for (int k = column_starts[j]; k < column_starts[j + 1]; ++k)
      if (rows[k] == j)
        d.segment(offsets[j], size(j)) = Eigen::Map<const Eigen::MatrixXd>(values[k], size(j), size(j)).diagonal();
  return d;
}

Eigen::SparseMatrix<double> BlockUpper::compressed(double shift) const {
  const int n = num_dofs();
  Eigen::SparseMatrix<double> H(n, n);
  H.resizeNonZeros(Eigen::Index(upper_nonzeros()));
  // The column starts first (a column's count follows from its block column's blocks), then
  // the block columns filled in parallel, each column in row order: the compressed arrays are
  // written directly.
  using Index = Eigen::SparseMatrix<double>::StorageIndex;
  Index* outer = H.outerIndexPtr();
  Index* inner = H.innerIndexPtr();
  double* out = H.valuePtr();
  outer[0] = 0;
  for (int j = 0; j < num_blocks(); ++j) {
    Index above = 0;  // entries of block column j above its diagonal block
    for (int k = column_starts[j]; k < column_starts[j + 1]; ++k)
      if (rows[k] != j) above += Index(size(rows[k]));
    const bool has_diagonal = column_starts[j] < column_starts[j + 1] && rows[column_starts[j + 1] - 1] == j;
    for (int c = 0; c < size(j); ++c) outer[offsets[j] + c + 1] = outer[offsets[j] + c] + above + (has_diagonal ? c + 1 : 0);
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, num_blocks(), 16), [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j < r.end(); ++j)
      for (int c = 0; c < size(j); ++c) {
        std::size_t e = std::size_t(outer[offsets[j] + c]);
        for (int k = column_starts[j]; k < column_starts[j + 1]; ++k) {
          const int i = rows[k], si = size(i);
          const int last = i == j ? c + 1 : si;  // a diagonal block's upper triangle
          for (int row = 0; row < last; ++row, ++e) {
            inner[e] = offsets[i] + row;
            out[e] = values[k][row + std::size_t(c) * si];
          }
          if (i == j) out[e - 1] += shift;
        }
      }
  });
  return H;
}

BlockRows block_rows(const BlockUpper& H) {
  const int n = H.num_blocks();
  BlockRows r;
  r.starts.assign(std::size_t(n) + 1, 0);
  for (int j = 0; j < n; ++j)
    for (int k = H.column_starts[j]; k < H.column_starts[j + 1]; ++k)
      if (H.rows[k] != j) ++r.starts[std::size_t(H.rows[k]) + 1];
  for (int i = 0; i < n; ++i) r.starts[std::size_t(i) + 1] += r.starts[std::size_t(i)];
  r.blocks.resize(std::size_t(r.starts.back()));
  std::vector<int> next(r.starts.begin(), r.starts.end() - 1);
  for (int j = 0; j < n; ++j)
    for (int k = H.column_starts[j]; k < H.column_starts[j + 1]; ++k)
      if (H.rows[k] != j) r.blocks[std::size_t(next[std::size_t(H.rows[k])]++)] = {k, j};
  return r;
}

Eigen::VectorXd BlockUpper::multiply(const Eigen::VectorXd& x, double shift) const {
  return multiply(x, shift, block_rows(*this));
}

Eigen::VectorXd BlockUpper::multiply(const Eigen::VectorXd& x, double shift, const BlockRows& by_row) const {
  const int n = num_blocks();
  const auto add = [&](int k, int j, Part target, Eigen::VectorXd& y) {
    const int i = rows[k];
    if (size(i) == 12 && size(j) == 12)
      multiply_block<12>(values[k], i, j, target, *this, shift, x, y);
    else if (size(i) == 3 && size(j) == 3)
      multiply_block<3>(values[k], i, j, target, *this, shift, x, y);
    else
      multiply_block<Eigen::Dynamic>(values[k], i, j, target, *this, shift, x, y);
  };
  // Block m of y in parallel, each summed in the order of a serial sweep over the columns:
  // column m's blocks (the diagonal one last), then row m's blocks in later columns.
  Eigen::VectorXd y = Eigen::VectorXd::Zero(x.size());
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 32), [&](const tbb::blocked_range<int>& r) {
    for (int m = r.begin(); m < r.end(); ++m) {
      for (int k = column_starts[m]; k < column_starts[m + 1]; ++k) add(k, m, Part::Column, y);
      for (int e = by_row.starts[std::size_t(m)]; e < by_row.starts[std::size_t(m) + 1]; ++e)
        add(by_row.blocks[std::size_t(e)][0], by_row.blocks[std::size_t(e)][1], Part::Row, y);
    }
  });
  return y;
}

GatheredBlocks gather_blocks(const Eigen::SparseMatrix<double>& upper, const std::vector<int>& sizes) {
  const int n = int(upper.rows());
  GatheredBlocks g;
  BlockUpper& H = g.blocks;
  for (int s : sizes) H.offsets.push_back(H.offsets.back() + s);
  if (upper.cols() != n || H.num_dofs() != n)
    throw std::invalid_argument("BlockCholesky: DOF blocks of " + std::to_string(H.num_dofs()) + " DOFs for a " +
                                std::to_string(n) + " × " + std::to_string(upper.cols()) + " matrix");
  const int nb = H.num_blocks();
  std::vector<int> block_of(n);
  for (int b = 0; b < nb; ++b) std::fill(block_of.begin() + H.offsets[b], block_of.begin() + H.offsets[b + 1], b);
  // Which blocks each block column stores (rows ascending, its diagonal block always), and
  // where each one starts in the pool.
  std::vector<int> slot_of(nb, -1);
  std::vector<std::size_t> at;
  std::size_t pool = 0;
  for (int J = 0; J < nb; ++J) {
    const int first = int(H.rows.size());
    for (int c = H.offsets[J]; c < H.offsets[J + 1]; ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(upper, c); it; ++it) {
        if (it.row() > c) throw std::invalid_argument("BlockCholesky: an entry below the diagonal");
        const int I = block_of[it.row()];
        if (slot_of[I] != J) slot_of[I] = J, H.rows.push_back(I);
      }
    if (slot_of[J] != J) slot_of[J] = J, H.rows.push_back(J);
    std::sort(H.rows.begin() + first, H.rows.end());
    for (int k = first; k < int(H.rows.size()); ++k) {
      at.push_back(pool);
      pool += std::size_t(H.size(H.rows[k])) * H.size(J);
    }
    H.column_starts.push_back(int(H.rows.size()));
  }
  g.pool.assign(pool, 0.0);
  std::vector<int> k_of(nb, -1);
  for (int J = 0; J < nb; ++J) {
    for (int k = H.column_starts[J]; k < H.column_starts[J + 1]; ++k) k_of[H.rows[k]] = k;
    for (int c = H.offsets[J]; c < H.offsets[J + 1]; ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(upper, c); it; ++it) {
        const int I = block_of[it.row()], k = k_of[I];
        g.pool[at[k] + std::size_t(it.row() - H.offsets[I]) + std::size_t(c - H.offsets[J]) * H.size(I)] = it.value();
      }
  }
  for (std::size_t k = 0; k < at.size(); ++k) H.values.push_back(g.pool.data() + at[k]);
  return g;
}

}  // namespace stiffsoft
