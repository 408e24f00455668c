#pragma once
/// @file PETSc Krylov solvers (KSP) on a block-sparse matrix with 3×3 blocks (BAIJ or SBAIJ,
/// bs = 3; MPIBAIJ over PETSC_COMM_WORLD under mpirun) behind the LinearSolver interface.

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <stiffsoft/coupling/linear_solver/block_sparse_pattern.hpp>
#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>

namespace stiffsoft {

/// What the PETSc backend does when its Krylov solve fails.
enum class KrylovFallback {
  None,    ///< report the failure; solve() returns NaN (Newton then regularises H)
  Cholmod  ///< solve the same system with CHOLMOD (every rank redundantly under MPI) and report that
};

/// Settings of the PETSc backend; PETSc's options database (-ksp_type, -pc_type, -ksp_rtol,
/// -ksp_max_it, -ksp_monitor, -pc_gamg_…, -log_view) applies on top of them.
struct PetscSolverSettings {
  std::string ksp_type = "cg";  ///< Krylov method: "cg", "minres" or "gmres"
  std::string pc_type = "icc";  ///< preconditioner: "none", "jacobi", "pbjacobi" (3×3 blocks),
                                ///< "vpbjacobi" (DOF blocks: 12×12 / 3×3), "icc", "gamg", "hypre"
  double relative_tolerance = kKrylovRelativeTolerance;  ///< η: stop when ‖b − H p‖ ≤ η ‖b‖ (set_relative_tolerance() changes it)
  int max_iterations = kKrylovIterationCap;  ///< Krylov iteration cap per solve
  std::string matrix_type;    ///< "baij", "sbaij" or "aij" (all with block size 3); empty: chosen
                              ///< per PC (see default_matrix_type()); -mat_type overrides
  KrylovFallback fallback = KrylovFallback::Cholmod;  ///< on a Krylov failure
  bool distributed = true;        ///< PETSC_COMM_WORLD (MPIBAIJ when it has > 1 rank); false: PETSC_COMM_SELF
  bool gamg_translations = true;  ///< GAMG: near-null space = the 3 translations (the p part of a
                                  ///< 12-block, every 3-block) instead of PETSc's per-component constants
  bool use_options_database = true;  ///< apply the PETSc options database (KSPSetFromOptions)
};

/// PETSc KSP solver of H p = b with H symmetric positive definite.
///
/// analyze_pattern() builds the BAIJ/SBAIJ matrix (bs = 3) preallocated from the pattern (and
/// keeps everything when given the pattern it analysed last);
/// factorize() copies the values into it (no new allocation while the pattern is unchanged)
/// and sets up the preconditioner; solve() runs the Krylov method with a zero initial guess
/// and returns p on every rank. The reported residual is the true ‖b − H p‖/‖b‖; when the
/// Krylov stopping test (e.g. MINRES's preconditioned norm) met the tolerance but the true
/// residual did not, the solve continues from p with a tighter tolerance (up to 4 passes).
///
/// Under MPI every rank passes the same H and b (each assembles the whole system); rank r
/// sets only its rows (a contiguous range of whole DOF blocks), the solve is distributed, and
/// the solution is gathered to every rank (VecScatterCreateToAll). In parallel "icc" becomes
/// block Jacobi over the ranks with ICC on each rank's block (-sub_pc_type icc).
class PetscSolver final : public LinearSolver {
 public:
  /// Starts PETSc if needed (ensure_petsc_initialized()) and creates the KSP; throws
  /// std::invalid_argument for an unknown KSP or PC name, or "hypre" without hypre in PETSc.
  explicit PetscSolver(const PetscSolverSettings& settings = {});
  /// Destroys the PETSc objects (unless PETSc was already finalised).
  ~PetscSolver() override;
  /// See LinearSolver; builds and preallocates the PETSc matrix.
  void analyze_pattern(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver; copies values, sets up the preconditioner. False when the
  /// preconditioner failed (block-Jacobi block or ICC pivot not positive) and the fallback,
  /// if any, found H not positive definite either.
  bool factorize(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver; keeps everything when given the blocks it analysed last.
  void analyze_blocks(const BlockUpper& H) override;
  /// See LinearSolver. On one rank (without the "vpbjacobi" shell) the values are copied from
  /// H's blocks into PETSc's 3×3 blocks without a compressed matrix; the fallback forms one
  /// only if it runs. Otherwise the compressed H is built where the fallback keeps it.
  bool factorize_blocks(const BlockUpper& H, double shift) override;
  /// See LinearSolver.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override;
  /// "petsc:KSP:PC" with the types in use (after the options database).
  std::string name() const override;
  /// See LinearSolver; ignored when -ksp_rtol is in the options database (the user's choice wins).
  void set_relative_tolerance(double eta) override;
  /// True.
  bool is_iterative() const override { return true; }
  /// See LinearSolver.
  void set_block_sizes(const std::vector<int>& sizes) override;
  /// How many times a PETSc matrix was created and preallocated (pattern analyses).
  int preallocations() const;
  /// This rank's row range [first, second) of the distributed matrix.
  std::pair<int, int> owned_rows() const;

 private:
  /// factorize()'s work once the values are gathered (into PETSc's own array when `in_petsc`,
  /// else into the pattern's): the PETSc matrix, the preconditioner, the fallback on failure.
  /// `upper` (the compressed H) only for the shell preconditioner.
  bool factorize_values(const Eigen::SparseMatrix<double>* upper, bool in_petsc,
                        std::chrono::steady_clock::time_point start);

  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// Throws std::invalid_argument for an unknown KSP or PC name, "hypre" without hypre in this
/// PETSc build, a tolerance outside (0, 1) or an iteration cap below 1; starts nothing.
void check_petsc_method(const PetscSolverSettings& settings);

/// The PETSc matrix type a preconditioner works best with (measured; see the .cpp).
std::string default_matrix_type(const std::string& pc_type);

/// The method "petsc" (no KSP/PC given) stands for; chosen from the measurements in
/// docs/benchmarks.md (see bench/linear_solver_bench.cpp).
PetscSolverSettings default_petsc_method();

}  // namespace stiffsoft
