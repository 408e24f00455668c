#pragma once
/// @file The global Hessian over the DOF blocks of q (12 wide for an affine body, 3 for a soft
/// node), assembled in dense blocks (one per pair of blocks that interact) and turned into a
/// sparse matrix for the linear solver.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <atomic>
#include <cstdint>
#include <vector>

#include <stiffsoft/coupling/linear_solver/block_upper.hpp>
#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// Symmetric block-sparse matrix over variable-size DOF blocks; only blocks (i, j) with i ≤ j
/// are stored, each dense and column-major in one pool. Of a diagonal block only the upper
/// triangle is the matrix (as BlockUpper reads it): its lower one may hold anything.
///
/// Meant to be reused: clear() starts the next assembly but keeps the storage of every block
/// seen so far, so that assembling the same pattern again allocates nothing and finds each
/// block by a short scan of its row (no hashing). The matrix is what was added since the last
/// clear(): blocks not touched since then are not part of it (nor of its pattern).
class BlockHessian {
 public:
  /// An empty matrix over the given DOF blocks (contiguous, in order).
  explicit BlockHessian(const std::vector<DofBlock>& blocks);
  /// Starts a new assembly: the matrix becomes zero with an empty off-diagonal pattern; the
  /// storage stays for reuse.
  void clear();
  /// Adds H (size_i × size_j) to block (i, j); for i > j the transpose is added to (j, i).
  /// A diagonal block (i = j) touches nothing shared: threads may add different ones at once.
  void add(int i, int j, const Eigen::Ref<const Eigen::MatrixXd>& H);
  /// Adds the size_i × size_j column-major block stored at `values` to block (i, j), i ≤ j; of
  /// a diagonal block (i = j) only the upper triangle is read.
  void add_upper(int i, int j, const double* values);
  /// add_upper where block (i, j) has storage already (every diagonal block has), without
  /// creating it: false, adding nothing, where it has none. Threads may call it at once for
  /// blocks of different rows i (owned_assembly.hpp).
  bool add_upper_stored(int i, int j, const double* values);
  /// Whether block (i, j), i < j, has storage (was ever part of the matrix).
  bool stored(int i, int j) const;
  /// Zeroes every off-diagonal block in the row or column of a block with held[b] ≠ 0 (DOFs
  /// held on a prescribed motion): those blocks then decouple from the rest. The sparsity
  /// pattern stays as it was.
  void decouple(const std::vector<char>& held);
  /// The upper triangle in place: its live blocks by block column, each column's by ascending
  /// row with the diagonal block last. Valid until the matrix changes.
  BlockUpper upper_blocks() const;
  /// The upper triangle as a compressed sparse column matrix (n × n, n = number of DOFs).
  Eigen::SparseMatrix<double> upper() const;
  /// The off-diagonal block pairs (key i·n + j, i < j), sorted: equal lists mean equal
  /// sparsity patterns.
  std::vector<std::int64_t> pattern() const;
  /// A number for the current sparsity pattern: two readings from one BlockHessian are equal
  /// only if the patterns are (the same pattern assembled again after clear() keeps its
  /// number, so a solver need not analyse it again).
  std::uint64_t pattern_version() const;
  /// y = H x for the full symmetric matrix.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;
  /// Number of blocks per side.
  int num_blocks() const { return int(m_blocks.size()); }
  /// Off-diagonal blocks with storage: those of the current matrix and others seen before,
  /// at most about twice the previous matrix's (clear()).
  std::size_t stored_blocks() const { return m_slots.size(); }

 private:
  using Block = Eigen::Map<Eigen::MatrixXd>;
  using ConstBlock = Eigen::Map<const Eigen::MatrixXd>;
  /// One stored off-diagonal block (row < column).
  struct Slot {
    int row, column;
    std::size_t at;             ///< pool offset
    std::uint64_t generation;   ///< the assembly that last touched it
  };
  Block block_at(std::size_t at, int i, int j) {
    return Block(m_pool.data() + at, m_blocks[i].size, m_blocks[j].size);
  }
  ConstBlock block_at(std::size_t at, int i, int j) const {
    return ConstBlock(m_pool.data() + at, m_blocks[i].size, m_blocks[j].size);
  }
  /// The slot of block (row, column), row < column, created if new; zeroed and marked live on
  /// its first touch in this assembly.
  Slot& live_slot(int row, int column);
  /// live_slot's slot where it exists, else null (nothing created): what threads adding to
  /// different rows may call at once.
  Slot* stored_slot(int row, int column);
  /// Drops the storage of every block not live in the current assembly (called by clear()
  /// before it starts the next one).
  void keep_only_live_slots();
  /// Adds `values` to the off-diagonal block at pool offset `at`, (i, j) with i < j.
  void add_off_diagonal(std::size_t at, int i, int j, const double* values);
  /// Whether a slot is part of the current matrix.
  bool live(const Slot& s) const { return s.generation == m_generation; }
  /// The live slots by block column, each column's by ascending row: column j's are
  /// slots[offsets[j] .. offsets[j + 1]).
  struct ColumnSlots {
    std::vector<int> offsets, slots;
  };
  /// The live slots grouped by block column (a counting sort, two allocations).
  ColumnSlots column_slots() const;

  std::vector<DofBlock> m_blocks;
  int m_num_dofs = 0;
  std::vector<double> m_pool;                 // dense blocks, column-major
  std::vector<std::size_t> m_diagonal;        // pool offset of block (i, i)
  std::size_t m_diagonal_size = 0;            // the diagonal blocks fill the pool's start
  std::vector<Slot> m_slots;                  // every off-diagonal block ever stored
  /// A row's stored block: its column beside its slot, so that finding it reads one array.
  struct RowEntry {
    int column, slot;
  };
  std::vector<std::vector<RowEntry>> m_row_slots;  // per block row: its slots, in creation order
  std::uint64_t m_generation = 1;               // the current assembly
  /// A count that threads adding to different blocks raise at once, copied with the matrix.
  struct SharedCount {
    std::atomic<std::size_t> n = 0;
    SharedCount() = default;
    SharedCount(const SharedCount& o) : n(o.n.load()) {}
    SharedCount& operator=(const SharedCount& o) {
      n = o.n.load();
      return *this;
    }
    void raise() { n.fetch_add(1, std::memory_order_relaxed); }
  };
  SharedCount m_live;                   // live slots now
  std::size_t m_previous_live = 0;      // live slots at the end of the previous assembly
  SharedCount m_grown;                  // slots live now and not at the end of the previous assembly
  std::uint64_t m_previous_version = 0;         // pattern_version() at the end of the previous assembly
};

}  // namespace stiffsoft
