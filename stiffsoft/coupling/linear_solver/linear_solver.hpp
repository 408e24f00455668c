#pragma once
/// @file The linear-solver interface of Newton's step: analyse a sparsity pattern once, then
/// factor (or set up) and solve many systems with it. Backends plug in behind it.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <stiffsoft/coupling/linear_solver/block_upper.hpp>
#include <stiffsoft/coupling/linear_solver/linear_solve_report.hpp>

namespace stiffsoft {

/// The Krylov backends' (PETSc's and "block_cg") relative tolerance η of a solve until
/// set_relative_tolerance() sets it.
inline constexpr double kKrylovRelativeTolerance = 1e-8;
/// The Krylov backends' iteration cap of one solve.
inline constexpr int kKrylovIterationCap = 1000;

/// What a solver's later choices depend on besides the systems it is given: "auto"'s backend
/// and the pattern size it chose it at (AutoSolver keeps a choice until the pattern changes by
/// more than kAutoRedecideChange). A resumed run gives it back (SimulationState), so that it
/// chooses as the uninterrupted run did.
struct LinearSolverMemory {
  long decided_nonzeros = -1;  ///< stored entries of the pattern the backend was chosen at; −1: none chosen
  bool krylov = false;         ///< whether the chosen backend is the Krylov one
};

/// Solves H p = b for symmetric positive (semi-)definite H given by its upper triangle
/// (compressed sparse column, n × n, n a multiple of 3).
///
/// Call order: analyze_pattern(H) whenever the pattern changes, then per system factorize(H),
/// solve(b). On failure solve() returns a vector of NaN (never a silently bad direction) and
/// last_report() says why; a caller that only checks `p.allFinite()` stays correct.
class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Symbolic analysis of the upper triangle's pattern; called again only when it changes.
  virtual void analyze_pattern(const Eigen::SparseMatrix<double>& upper) = 0;
  /// Numeric factorisation (or set-up); returns false when H is not positive definite
  /// (numerically), in which case solve() must not be called.
  virtual bool factorize(const Eigen::SparseMatrix<double>& upper) = 0;
  /// analyze_pattern() for H given by its upper triangle in dense DOF blocks (Newton's assembled
  /// Hessian, read in place). By default through H.compressed(); a block backend reads the blocks.
  virtual void analyze_blocks(const BlockUpper& H) { analyze_pattern(H.compressed()); }
  /// factorize() of H + shift·I, H given as for analyze_blocks(). By default through
  /// H.compressed(shift); a block backend copies the blocks without forming a CSC.
  virtual bool factorize_blocks(const BlockUpper& H, double shift) { return factorize(H.compressed(shift)); }
  /// The solution of H p = b with the last factorised H; all NaN when the solve failed.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& b) = 0;
  /// The backend's name, for logs and stats.
  virtual std::string name() const = 0;

  /// Relative tolerance η of the following solves: ‖b − H p‖ ≤ η ‖b‖ (inexact Newton, see
  /// forcing_term.hpp). Ignored by direct backends, which solve to round-off.
  virtual void set_relative_tolerance(double eta) { (void)eta; }
  /// True for Krylov backends, whose cost depends on the tolerance η.
  virtual bool is_iterative() const { return false; }
  /// Sizes of the consecutive DOF blocks of q (12 for an affine body, 3 for a soft node;
  /// Σ sizes = n), for block preconditioners and for splitting rows over MPI ranks without
  /// cutting a block. Call before analyze_pattern(); without it a backend infers the blocks
  /// from the pattern (see BlockSparsePattern). Ignored by direct backends.
  virtual void set_block_sizes(const std::vector<int>& sizes) { (void)sizes; }
  /// The choices so far that later ones depend on (LinearSolverMemory); none by default.
  virtual LinearSolverMemory memory() const { return {}; }
  /// Takes `memory` from another solver of the same kind and settings as its own, before the
  /// first analysis. Ignored by solvers without memory.
  virtual void restore_memory(const LinearSolverMemory& memory) { (void)memory; }
  /// What the last factorize()/solve() pair did.
  const LinearSolveReport& last_report() const { return m_report; }

 protected:
  LinearSolveReport m_report;  ///< filled in by the backend in factorize() and solve()
};

/// The backend called `name`; throws std::invalid_argument for an unknown one. Names:
///  - "cholmod": CHOLMOD Cholesky (supernodal or simplicial, see CholmodSolver);
///  - "block_cholesky": Cholesky over the dense DOF blocks (see BlockCholeskySolver);
///  - "block_cg": conjugate gradients with IC(0) over the dense DOF blocks (see BlockCholeskySolver);
///  - "petsc": PETSc KSP with the default method (see default_petsc_method());
///  - "petsc:KSP" or "petsc:KSP:PC": KSP ∈ {cg, minres, gmres}, PC ∈ {none, jacobi, pbjacobi
///    (3×3 blocks), vpbjacobi (DOF blocks, 12×12 / 3×3), icc, gamg, hypre (BoomerAMG)}, e.g.
///    "petsc:cg:gamg"; PETSc's options database (-ksp_type, -pc_type, -ksp_rtol, …) applies on top;
///  - "auto": a direct or a Krylov backend chosen from the predicted factorisation cost (see AutoSolver);
///  - any name added with register_linear_solver().
/// PETSc backends start PETSc (ensure_petsc_initialized()) if main has not.
std::unique_ptr<LinearSolver> make_linear_solver(const std::string& name);

/// Throws std::invalid_argument (the same message as make_linear_solver()) when `name` is not
/// a backend name; creates nothing and does not start PETSc. For the scene loader's checks.
void check_linear_solver_name(const std::string& name);

/// Makes make_linear_solver(name) return factory(); replaces an earlier registration of the
/// same name (built-in names cannot be replaced). For tools that wrap a backend (e.g. the
/// benchmark's recorder). Not thread-safe: register before creating solvers.
void register_linear_solver(const std::string& name, std::function<std::unique_ptr<LinearSolver>()> factory);

/// The names make_linear_solver() accepts (built-in families and registered names), for errors.
std::vector<std::string> linear_solver_names();

}  // namespace stiffsoft
