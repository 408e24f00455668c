#pragma once
/// @file The "auto" linear solver: a direct factorisation when it is cheap (the block Cholesky
/// for piles of affine bodies, CHOLMOD otherwise), conjugate gradients with IC(0) when it is
/// not (over the DOF blocks for piles of affine bodies, PETSc's ICC(0) otherwise), from the
/// factorisation's own prediction of its cost.

#include <functional>
#include <memory>

#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>

namespace stiffsoft {

/// Predicted factorisation cost (the symbolic analysis' flop count, cholmod_common::fl) up to
/// which "auto" keeps CHOLMOD when there are soft nodes. From
/// bench/linear_solver_bench (docs/benchmarks.md, "Linear solvers"): the rigid pile `medium` (0.98 Mflop) was factorised and solved by CHOLMOD in 1.3
/// ms against 3.8 ms for CG + ICC(0) at η = 1e-8 (1.1 ms at 1e-3), while every system above
/// 2.8 Mflop (hybrid and soft scenes, `full`, 3D lattices) was solved 2× to 100× faster by
/// CG + ICC(0) than by CHOLMOD (reference BLAS, 2 busy cores).
constexpr double kAutoCholmodFlops = 2e6;

/// The same bound for the block Cholesky (BlockCholesky::flops(); affine bodies only), whose
/// fixed 12×12 kernels run far faster per flop than CHOLMOD's simplicial factor. Measured at one thread against
/// CG + ICC(0), solve phase per Newton iteration (docs/benchmarks.md, session 20): `full` at
/// t = 0.67 s (6.1 Mflop) 4.4 ms against 8.4; `bricks_900` at 15–18 Mflop 4.4–17 ms against
/// 9.7–20, at 103 Mflop 30 ms against 19.
constexpr double kAutoBlockCholeskyFlops = 2e7;

/// Rows from which "auto" takes the Krylov method without asking CHOLMOD: its analysis alone
/// costs about as much as a Krylov solve there (81 000 rows: 1 s against 0.4–0.7 s). The block
/// Cholesky is asked at any size, but not again above it after giving way to block_cg while the
/// pattern grows: its analysis of a 5,000-body pile took 1–7 ms (full's kind, which it then
/// factorised at 12 Mflop, the solve phase half of block_cg's) to 0.6 s (a 5,066-cube pile at
/// 34 Gflop, left to block_cg; docs/benchmarks.md, session 72).
constexpr int kAutoKrylovRows = 50000;

/// The analysis is repeated only when the number of stored entries moved by more than this
/// fraction since the last decision (contacts come and go at every few Newton iterations).
constexpr double kAutoRedecideChange = 0.25;

/// Delegates to a direct solver or to a Krylov one: when every DOF block given by
/// set_block_sizes() is an affine body's 12, the block Cholesky (its 12×12 dense blocks factorise
/// 2.7–3.4× faster than CHOLMOD's simplicial method, docs/benchmarks.md) analyses the pattern and
/// is kept when it predicts at most kAutoBlockCholeskyFlops (above kAutoKrylovRows rows it is not
/// asked again after giving way to block_cg while the pattern grows); with soft nodes, below
/// kAutoKrylovRows rows, CHOLMOD analyses it and is kept at most kAutoCholmodFlops for the
/// factorisation (soft nodes' 3×3 blocks fill like a 3-D mesh,
/// which CHOLMOD's supernodes and PETSc handle better); otherwise "block_cg" when every DOF
/// block is an affine body's (its 12×12 IC(0) in parallel, solve phase 1.5–1.9× cheaper than
/// PETSc's on `bricks_900` at one thread, docs/benchmarks.md) and PETSc
/// (default_petsc_method()) when there are soft nodes (there "block_cg" is the same
/// preconditioner but 2.5–2.8× slower: docs/linear_solvers.md). The decision is
/// revisited at an analyze_pattern() whose number of stored entries differs by more than
/// kAutoRedecideChange from the last decision's.
class AutoSolver final : public LinearSolver {
 public:
  /// Nothing chosen yet.
  AutoSolver();
  /// Frees the chosen backend.
  ~AutoSolver() override;
  /// Chooses the backend (see the class comment), which then has analysed the pattern.
  void analyze_pattern(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver.
  bool factorize(const Eigen::SparseMatrix<double>& upper) override;
  /// Chooses as analyze_pattern() does; the chosen backend reads the blocks its own way.
  void analyze_blocks(const BlockUpper& H) override;
  /// See LinearSolver.
  bool factorize_blocks(const BlockUpper& H, double shift) override;
  /// See LinearSolver.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override;
  /// "auto→" followed by the chosen backend's name, e.g. "auto→cholmod".
  std::string name() const override;
  /// Kept and passed on to a Krylov backend.
  void set_relative_tolerance(double eta) override;
  /// True when the chosen backend is iterative.
  bool is_iterative() const override;
  /// Kept and passed on to the chosen backend.
  void set_block_sizes(const std::vector<int>& sizes) override;
  /// The chosen backend's kind and the stored entries it was chosen at.
  LinearSolverMemory memory() const override;
  /// The next analysis takes the remembered kind of backend without deciding (unless the
  /// pattern moved by more than kAutoRedecideChange from the remembered size).
  void restore_memory(const LinearSolverMemory& memory) override;

 private:
  /// The decision of analyze_pattern() for a matrix of `rows` rows and `nonzeros` stored entries
  /// of its upper triangle; `analyse` has a backend analyse the matrix.
  void choose(long nonzeros, int rows, const std::function<void(LinearSolver&)>& analyse);

  /// A new backend of the remembered kind for a matrix of `rows` rows, not analysed.
  std::unique_ptr<LinearSolver> make_backend(bool krylov, int rows) const;
  /// Whether every DOF block given by set_block_sizes() is an affine body's, over `rows` rows.
  bool affine_bodies_only(int rows) const;

  std::unique_ptr<LinearSolver> m_backend;
  LinearSolverMemory m_choice;  // the last decision: its stored entries and backend kind
  double m_eta = 0;
  std::vector<int> m_block_sizes;
};

}  // namespace stiffsoft
