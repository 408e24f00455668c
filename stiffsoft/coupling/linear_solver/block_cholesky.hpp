#pragma once
/// @file Sparse Cholesky factorisation over dense DOF blocks: L is stored block by block (an
/// affine body's 12×12, a soft node's 3×3), the fill-reducing ordering and the elimination
/// tree are those of the block graph, and every operation is a small dense one. The rigid
/// piles' factors are a few hundred 12×12 blocks with little fill, which CHOLMOD's simplicial
/// method treats one scalar column at a time and its supernodal one with a BLAS call per small
/// supernode; here each column is factorised as soon as the columns that update it are, on
/// whichever thread is free (the elimination tree's branches in parallel).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include <stiffsoft/coupling/linear_solver/block_upper.hpp>

namespace stiffsoft {

/// H = Pᵀ L Lᵀ P for a symmetric positive definite H given by its upper triangle in dense
/// blocks (BlockUpper, or a CSC whose blocks are gathered), with P a
/// permutation of whole DOF blocks (approximate minimum degree on the block graph) and L
/// lower triangular in dense blocks.
///
/// Deterministic: every block of L is computed by the same operations in the same order
/// whatever the thread count (a column runs once the columns it reads are complete, and writes
/// only its own blocks), so factors and solutions are the same bit for bit.
///
/// With Fill::None it is the incomplete factorisation IC(0) over the blocks instead: the DOF
/// blocks in their own order, L keeping exactly the blocks of H (every update that would fill
/// another block dropped), a preconditioner for conjugate gradients. Its columns wait on the
/// same way: each on the earlier columns that update it.
class BlockCholesky {
 public:
  /// Which blocks of L the factorisation may fill.
  enum class Fill {
    Complete,  ///< the exact factor, in a fill-reducing order
    None       ///< IC(0): only the blocks H stores, in the blocks' own order
  };
  /// A factorisation of the given kind (the exact one by default).
  explicit BlockCholesky(Fill fill = Fill::Complete) : m_fill(fill) {}
  /// Symbolic analysis of H's block pattern: ordering, elimination tree, the block pattern of
  /// L and where each stored block of H goes. Throws std::invalid_argument when a stored
  /// block lies below the diagonal. The pattern analysed last keeps its analysis (and the
  /// factor kept for factorize()'s reuse).
  void analyze(const BlockUpper& H);
  /// analyze() of the blocks of `upper` (n × n CSC, entries with row ≤ column) over DOF blocks
  /// of the given sizes (Σ sizes = n; see gather_blocks(), which throws when they do not fit).
  void analyze(const Eigen::SparseMatrix<double>& upper, const std::vector<int>& sizes);
  /// Numeric factorisation of H + shift·I (H of the analysed pattern, else std::invalid_argument;
  /// std::logic_error before analyze()); false when a pivot block is not positive definite
  /// (numerically), after which solve() must not be called. After a successful factorisation
  /// of the same analysis, shift and boost, only the columns whose blocks changed and the
  /// columns they update are computed again (the same factor, bit for bit). `boost` > 0
  /// factorises H + shift·I + boost·diag(H) instead (Manteuffel's shift, for an IC(0) that
  /// breaks down on a positive definite H); multiply() keeps H + shift·I.
  bool factorize(const BlockUpper& H, double shift = 0, double boost = 0);
  /// factorize() of the blocks of `upper`, of the pattern analyze() was given (no shift).
  bool factorize(const Eigen::SparseMatrix<double>& upper, double boost = 0);
  /// Columns (DOF blocks) the last factorize() computed: all of them, or fewer when it could
  /// keep some from the factorisation before.
  std::size_t refactored_columns() const { return m_refactored; }
  /// x = H⁻¹ b with the last factor.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// y = (H + shift·I) x with the last successfully factorised H and shift, block by block;
  /// for residuals without a copy of H. Valid until the next analyze() or failed factorize().
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;
  /// H with the last successfully factorised numbers (a view into this factorisation's copy)
  /// and its shift: what multiply() multiplies by, for an exact factor to start from.
  const BlockUpper& factorised() const { return m_factorised; }
  /// The shift of the last successful factorisation.
  double shift() const { return m_shift; }
  /// Floating-point operations of one factorisation, from the symbolic analysis.
  double flops() const { return m_flops; }
  /// Scalar entries of L (its lower triangle, diagonal blocks' lower halves included).
  double nonzeros() const { return m_nonzeros; }
  /// Whether analyze() has been called.
  bool analysed() const { return !m_column_offsets.empty(); }

 private:
  /// Column j of L in the elimination order: one DOF block.
  struct Column {
    int size;                 ///< its width
    int offset;               ///< its first DOF in the original order
    std::size_t diagonal;     ///< pool offset of L_jj (size × size, column-major)
  };
  /// Block L_ij in the pool: row block i (permuted), pool offset.
  struct Entry {
    int row;
    std::size_t at;
  };
  /// Column k < j whose struct contains j, with the position of j in struct(k).
  struct Update {
    int column;
    int position;
  };
  /// Computes column j of L in place (its updates from earlier columns, then L_jj and the
  /// blocks below it); false when the pivot block is not positive definite. `slot` maps a block
  /// row to its entry in column j, −1 for the rows column j lacks (scratch of one thread, left
  /// all −1). S: the common block size or Dynamic.
  template <int S>
  bool factor_column(int j, std::vector<int>& slot);
  /// Starts column j of L from H + shift·I + boost·diag(H): its blocks of H copied into the
  /// pool, its fill-in zeroed. Each column owns its places in the pool, so columns load in parallel.
  void load_column(int j, const BlockUpper& H, double shift, double boost);
  /// x ← L⁻ᵀ L⁻¹ x (the original DOF order throughout: P only decides the order of columns), on
  /// the calling thread: a column's part costs about 0.3 µs, and on two threads the columns
  /// handed out cost more than they saved (docs/benchmarks.md, session 54).
  template <int S>
  void solve_in_place(Eigen::VectorXd& x) const;

  std::vector<Column> m_columns;                 // by permuted index
  std::vector<int> m_column_offsets;             // m_entries[m_column_offsets[j] …) = struct(j)
  std::vector<Entry> m_entries;                  // off-diagonal blocks of L, by column
  std::vector<int> m_update_offsets;             // m_updates[m_update_offsets[j] …): the k that update j
  std::vector<Update> m_updates;
  Fill m_fill;
  /// Where a stored block of H goes: L_jj's place (its upper triangle into L_jj's lower one),
  /// a block of L as it is, or a block of L transposed (when its block row comes first in the
  /// elimination order); `column` is the column of L that holds it.
  struct Target {
    enum Kind : char { Diagonal, AsIs, Transposed } kind;
    int column;
    std::size_t at;
    int block_column;  ///< the block column of H that stores it
  };
  std::vector<Target> m_target;                  // per stored block of H
  std::vector<int> m_input_offsets, m_inputs;    // m_inputs[m_input_offsets[j] …): the blocks of H column j of L holds
  /// A range of the pool that no block of H fills: a block of fill-in (or a diagonal block H
  /// lacks), zeroed before its column is computed again; the others are overwritten by H's.
  struct Unfilled {
    std::size_t at, count;
  };
  std::vector<int> m_unfilled_offsets;           // m_unfilled[m_unfilled_offsets[j] …): column j's
  std::vector<Unfilled> m_unfilled;
  std::vector<std::size_t> m_input_at;           // per stored block of H: where m_input holds it
  std::vector<double> m_input;                   // H's blocks at the last successful factorisation
  BlockUpper m_factorised;                       // H's pattern, its values in m_input
  BlockRows m_factorised_rows;                   // its blocks by row, for multiply()
  double m_shift = 0, m_boost = 0;               // … and the shift and boost factorised with them
  bool m_kept = false;                           // whether m_input, m_shift and m_boost hold a complete factor's H
  GatheredBlocks m_gathered;                     // the blocks of the last CSC given
  std::vector<double> m_pool;                    // L's blocks
  int m_uniform = 0;                             // the common block size, 0 when they differ
  double m_flops = 0, m_nonzeros = 0;
  std::size_t m_refactored = 0;
};

}  // namespace stiffsoft
