#include <stiffsoft/coupling/linear_solver/petsc_solver.hpp>

#include <petscksp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <stiffsoft/coupling/linear_solver/block_jacobi.hpp>
#include <stiffsoft/coupling/linear_solver/cholmod_solver.hpp>
#include <stiffsoft/coupling/linear_solver/petsc_session.hpp>

namespace stiffsoft {

namespace {

static_assert(sizeof(PetscInt) == sizeof(int), "the block pattern hands int indices to PETSc");
static_assert(sizeof(PetscScalar) == sizeof(double), "PETSc must be built with real double scalars");

/// Throws std::runtime_error naming the PETSc call that failed.
void check(PetscErrorCode ierr, const char* call) {
  if (ierr == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(ierr, &text, nullptr);
  throw std::runtime_error(std::string("PETSc backend: ") + call + " failed (PETSc error " +
                           std::to_string(ierr) + (text ? std::string(": ") + text : std::string()) +
                           "; PETSc's message is above)");
}
#define STIFFSOFT_PETSC(call) check((call), #call)

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

constexpr std::array<const char*, 3> kKspTypes{"cg", "minres", "gmres"};
constexpr std::array<const char*, 7> kPcTypes{"none", "jacobi", "pbjacobi", "vpbjacobi",
                                              "icc",  "gamg",   "hypre"};

/// Throws std::invalid_argument naming `what` and the available names unless `name` is one of `names`.
template <std::size_t N>
void check_known(const std::array<const char*, N>& names, const std::string& name, const char* what) {
  if (std::any_of(names.begin(), names.end(), [&](const char* n) { return name == n; })) return;
  std::string available;
  for (const char* n : names) available += (available.empty() ? "" : ", ") + std::string(n);
  throw std::invalid_argument(std::string("PETSc backend: unknown ") + what + " '" + name +
                              "' (available: " + available + ")");
}

bool has_option(const char* name) {
  PetscBool set = PETSC_FALSE;
  STIFFSOFT_PETSC(PetscOptionsHasName(nullptr, nullptr, name, &set));
  return set;
}

LinearSolveStatus status_of(KSPConvergedReason reason) {
  if (reason > 0) return LinearSolveStatus::Converged;
  switch (reason) {
    case KSP_DIVERGED_INDEFINITE_PC:
    case KSP_DIVERGED_INDEFINITE_MAT:
      return LinearSolveStatus::Indefinite;
    case KSP_DIVERGED_ITS:
      return LinearSolveStatus::IterationCap;
    case KSP_DIVERGED_PC_FAILED:
      return LinearSolveStatus::PreconditionerFailed;
    default:
      return LinearSolveStatus::Diverged;
  }
}

/// PCSHELL callback: y = blockdiag(H)⁻¹ x on this rank's rows.
PetscErrorCode apply_block_jacobi(PC pc, Vec x, Vec y) {
  void* context = nullptr;
  PetscCall(PCShellGetContext(pc, &context));
  const PetscScalar* xa = nullptr;
  PetscScalar* ya = nullptr;
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  static_cast<const BlockJacobi*>(context)->apply(xa, ya);
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  return 0;
}

/// Makes `pc` stiffsoft's "vpbjacobi": a PCSHELL applying the inverse diagonal DOF blocks
/// (analyze_pattern() hands it the BlockJacobi as its context).
void use_block_jacobi_shell(PC pc) {
  STIFFSOFT_PETSC(PCSetType(pc, PCSHELL));
  STIFFSOFT_PETSC(PCShellSetApply(pc, apply_block_jacobi));
  STIFFSOFT_PETSC(PCShellSetName(pc, "vpbjacobi: stiffsoft's inverse diagonal DOF blocks (12x12 / 3x3)"));
}

/// Throws std::invalid_argument unless 0 < η < 1.
void check_relative_tolerance(double eta) {
  if (!(eta > 0 && eta < 1))
    throw std::invalid_argument("PETSc backend: relative tolerance " + std::to_string(eta) +
                                "; expected in (0, 1)");
}

}  // namespace

std::string default_matrix_type(const std::string& pc_type) {
  // PETSc 3.18 factors ICC only for SBAIJ and AIJ; GAMG builds its graph only from AIJ
  // ("No method creategraph for Mat of type seqbaij"); BoomerAMG takes AIJ without conversion.
  // Sub-solvers of PETSc's block Jacobi (ILU by default, ICC) need AIJ or SBAIJ too.
  if (pc_type == "icc") return "sbaij";
  if (pc_type == "gamg" || pc_type == "hypre" || pc_type == "bjacobi" || pc_type == "asm") return "aij";
  return "baij";
}

void check_petsc_method(const PetscSolverSettings& settings) {
  check_known(kKspTypes, settings.ksp_type, "Krylov method");
  check_known(kPcTypes, settings.pc_type, "preconditioner");
#ifndef PETSC_HAVE_HYPRE
  if (settings.pc_type == "hypre")
    throw std::invalid_argument(
        "PETSc backend: this PETSc build has no hypre, so 'hypre' (BoomerAMG) is unavailable");
#endif
  check_relative_tolerance(settings.relative_tolerance);
  if (settings.max_iterations < 1)
    throw std::invalid_argument("PETSc backend: iteration cap " + std::to_string(settings.max_iterations) +
                                "; expected ≥ 1");
}

struct PetscSolver::Impl {
  PetscSolverSettings settings;
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0, size = 1;
  KSP ksp = nullptr;
  Mat A = nullptr;
  Mat P = nullptr;     // A + α diag(A): the preconditioner's matrix once ICC of A broke down
  double pc_shift = 0;  // that α; 0 while the preconditioner is built from A itself
  Vec x = nullptr, b = nullptr, r = nullptr, x_all = nullptr;
  VecScatter to_all = nullptr;
  std::optional<BlockSparsePattern> pattern;
  std::vector<double> values;
  std::vector<int> given_block_sizes, block_sizes;
  int n = 0, row_begin = 0, row_end = 0;
  std::unique_ptr<BlockJacobi> block_jacobi;
  bool shell = false;              // the PC in use is our block Jacobi
  std::string preconditioner;      // the PC in use, in our names ("vpbjacobi" for the shell)
  bool rtol_from_options = false;  // -ksp_rtol given: it wins over set_relative_tolerance()
  double rtol = kKrylovRelativeTolerance;
  int preallocations = 0;
  // Fallback (CHOLMOD on the whole system, on every rank).
  Eigen::SparseMatrix<double> upper;  // copy of the last factorised H, kept only with a fallback
  bool upper_current = true;  // false: `upper` is formed from the stored values when the fallback needs it
  // On one rank, once PETSc's own value array of the matrix is seen to hold the pattern's values
  // in the pattern's layout: the values go straight into it, without MatSetValuesBlocked.
  enum class InPlace { Unchecked, Yes, No } in_place = InPlace::Unchecked;
  CholmodSolver cholmod;
  bool cholmod_analyzed = false;
  bool cholmod_ready = false;  // factorize() already moved to the fallback
  std::string setup_failure;

  void destroy_matrix() {
    if (!PetscSession::running()) return;
    MatDestroy(&A);
    MatDestroy(&P);
    VecDestroy(&x);
    VecDestroy(&b);
    VecDestroy(&r);
    VecDestroy(&x_all);
    VecScatterDestroy(&to_all);
  }

  /// Calls f(a) with the value array of A, a sequential SBAIJ or BAIJ matrix (false otherwise:
  /// f is not called).
  template <class F>
  bool with_petsc_values(F&& f) {
    PetscBool sbaij = PETSC_FALSE, baij = PETSC_FALSE;
    STIFFSOFT_PETSC(PetscObjectTypeCompare((PetscObject)A, MATSEQSBAIJ, &sbaij));
    STIFFSOFT_PETSC(PetscObjectTypeCompare((PetscObject)A, MATSEQBAIJ, &baij));
    PetscScalar* a = nullptr;
    if (sbaij) {
      STIFFSOFT_PETSC(MatSeqSBAIJGetArray(A, &a));
      f(a);
      STIFFSOFT_PETSC(MatSeqSBAIJRestoreArray(A, &a));
    } else if (baij) {
      STIFFSOFT_PETSC(MatSeqBAIJGetArray(A, &a));
      f(a);
      STIFFSOFT_PETSC(MatSeqBAIJRestoreArray(A, &a));
    }
    return sbaij || baij;
  }

  /// Whether A's value array holds `values` in the pattern's layout: its block rows and columns
  /// are the pattern's and its numbers equal (checked once per analysis, after the first
  /// assembly through MatSetValuesBlocked).
  bool holds_values_in_place() {
    PetscInt rows = 0;
    const PetscInt *ia = nullptr, *ja = nullptr;
    PetscBool done = PETSC_FALSE;
    STIFFSOFT_PETSC(MatGetRowIJ(A, 0, PETSC_FALSE, PETSC_TRUE, &rows, &ia, &ja, &done));
    bool same = done && rows == pattern->num_block_rows() &&
                std::equal(pattern->row_offsets().begin(), pattern->row_offsets().end(), ia) &&
                std::equal(pattern->block_columns().begin(), pattern->block_columns().end(), ja);
    STIFFSOFT_PETSC(MatRestoreRowIJ(A, 0, PETSC_FALSE, PETSC_TRUE, &rows, &ia, &ja, &done));
    if (!same) return false;
    return with_petsc_values([&](const PetscScalar* a) {
             same = std::equal(values.begin(), values.end(), a);
           }) && same;
  }

  PC pc() const {
    PC p = nullptr;
    STIFFSOFT_PETSC(KSPGetPC(ksp, &p));
    return p;
  }

  std::string pc_type() const {
    PCType t = nullptr;
    STIFFSOFT_PETSC(PCGetType(pc(), &t));
    return t ? t : "";
  }

  std::string ksp_type() const {
    KSPType t = nullptr;
    STIFFSOFT_PETSC(KSPGetType(ksp, &t));
    return t ? t : "";
  }

  /// The preconditioner's set-up failure on any rank (PC_NOERROR when none): the lowest
  /// non-zero code, PC_SETUP_ERROR being −1.
  int preconditioner_failure() const {
    PCFailedReason reason = PC_NOERROR;
    STIFFSOFT_PETSC(PCGetFailedReasonRank(pc(), &reason));
    std::array<int, 2> codes{int(reason), -int(reason)};
    MPI_Allreduce(MPI_IN_PLACE, codes.data(), 2, MPI_INT, MPI_MAX, comm);
    return codes[1] > 0 ? -codes[1] : codes[0];
  }

  /// Rebuilds the preconditioner from P = A + α diag(A) with the next α (1e-3, 1e-2, … 1), for
  /// an ICC(0) that broke down or came out indefinite on a positive definite H: PETSc applies
  /// its Manteuffel shift to point (block size 1) matrices only, not to our 3×3-block ones.
  /// CG still solves with A. False when the preconditioner is not ICC or α would pass 1.
  bool shift_preconditioner() {
    if (pc_type() != PCICC) return false;
    Vec diagonal = nullptr, shift = nullptr;
    STIFFSOFT_PETSC(VecDuplicate(x, &diagonal));
    STIFFSOFT_PETSC(VecDuplicate(x, &shift));
    STIFFSOFT_PETSC(MatGetDiagonal(A, diagonal));
    bool built = false;
    for (double alpha = pc_shift == 0 ? 1e-3 : 10 * pc_shift; alpha <= 1 && !built; alpha *= 10) {
      if (P) STIFFSOFT_PETSC(MatCopy(A, P, SAME_NONZERO_PATTERN));
      else STIFFSOFT_PETSC(MatDuplicate(A, MAT_COPY_VALUES, &P));
      STIFFSOFT_PETSC(VecAXPBY(shift, alpha, 0.0, diagonal));  // shift = α diag(A)
      STIFFSOFT_PETSC(MatDiagonalSet(P, shift, ADD_VALUES));
      STIFFSOFT_PETSC(KSPSetOperators(ksp, A, P));
      STIFFSOFT_PETSC(KSPSetUp(ksp));
      pc_shift = alpha;
      built = preconditioner_failure() == int(PC_NOERROR);
    }
    STIFFSOFT_PETSC(VecDestroy(&diagonal));
    STIFFSOFT_PETSC(VecDestroy(&shift));
    return built;
  }

  /// The near-null space of GAMG: the three translations (p of a 12-block, a 3-block itself).
  void set_translation_near_null_space() {
    std::array<Vec, 3> modes{};
    for (int k = 0; k < 3; ++k) {
      STIFFSOFT_PETSC(VecDuplicate(x, &modes[k]));
      PetscScalar* a = nullptr;
      STIFFSOFT_PETSC(VecGetArray(modes[k], &a));
      std::fill(a, a + (row_end - row_begin), 0.0);
      int row = 0;
      for (const int s : block_sizes) {
        if (row >= row_begin && row < row_end) a[row - row_begin + k] = 1.0;
        row += s;
      }
      STIFFSOFT_PETSC(VecRestoreArray(modes[k], &a));
      STIFFSOFT_PETSC(VecNormalize(modes[k], nullptr));
    }
    MatNullSpace space = nullptr;
    STIFFSOFT_PETSC(MatNullSpaceCreate(comm, PETSC_FALSE, 3, modes.data(), &space));
    STIFFSOFT_PETSC(MatSetNearNullSpace(A, space));
    STIFFSOFT_PETSC(MatNullSpaceDestroy(&space));
    for (Vec& v : modes) STIFFSOFT_PETSC(VecDestroy(&v));
  }

  /// Factorises the kept copy of H (`upper`, formed first from the stored values when
  /// factorize_blocks() left it out) with CHOLMOD, analysing its pattern once per pattern;
  /// false when H is not positive definite.
  bool factorize_fallback() {
    if (!upper_current) {
      if (in_place == InPlace::Yes) {
        with_petsc_values([&](const PetscScalar* a) { upper = pattern->upper(a); });
      } else {
        upper = pattern->upper(values.data());
      }
    }
    upper_current = true;
    if (!cholmod_analyzed) cholmod.analyze_pattern(upper);
    cholmod_analyzed = true;
    cholmod_ready = cholmod.factorize(upper);
    return cholmod_ready;
  }

  /// The CHOLMOD solution of the last factorised H (identical on every rank: rank 0's is broadcast),
  /// reported as the fallback's answer after the primary method failed for `primary_failure`.
  Eigen::VectorXd cholmod_solve(const Eigen::VectorXd& rhs, const std::string& primary_failure,
                                LinearSolveReport& report) {
    if (!cholmod_ready) factorize_fallback();
    Eigen::VectorXd p = cholmod_ready
                            ? cholmod.solve(rhs)
                            : Eigen::VectorXd::Constant(rhs.size(), std::numeric_limits<double>::quiet_NaN());
    if (size > 1) MPI_Bcast(p.data(), int(p.size()), MPI_DOUBLE, 0, comm);
    const LinearSolveReport& c = cholmod.last_report();
    report.fallback_used = true;
    report.primary_failure = primary_failure;
    report.status =
        cholmod_ready && p.allFinite() ? LinearSolveStatus::Converged : LinearSolveStatus::Indefinite;
    report.reason = cholmod_ready ? c.reason : "CHOLMOD: the matrix is not positive definite";
    report.relative_residual = c.relative_residual;
    return p;
  }
};

PetscSolver::PetscSolver(const PetscSolverSettings& settings) : m_impl(std::make_unique<Impl>()) {
  Impl& m = *m_impl;
  m.settings = settings;
  check_petsc_method(settings);
  ensure_petsc_initialized();
  m.comm = settings.distributed ? PETSC_COMM_WORLD : PETSC_COMM_SELF;
  MPI_Comm_rank(m.comm, &m.rank);
  MPI_Comm_size(m.comm, &m.size);
  m.rtol = settings.relative_tolerance;

  STIFFSOFT_PETSC(KSPCreate(m.comm, &m.ksp));
  STIFFSOFT_PETSC(KSPSetType(m.ksp, settings.ksp_type.c_str()));
  STIFFSOFT_PETSC(KSPSetTolerances(m.ksp, m.rtol, PETSC_DEFAULT, PETSC_DEFAULT, settings.max_iterations));
  PC pc = m.pc();
  if (settings.pc_type == "vpbjacobi") {
    use_block_jacobi_shell(pc);
  } else if (settings.pc_type == "hypre") {
#ifdef PETSC_HAVE_HYPRE
    STIFFSOFT_PETSC(PCSetType(pc, PCHYPRE));
    STIFFSOFT_PETSC(PCHYPRESetType(pc, "boomeramg"));
#endif
  } else {
    STIFFSOFT_PETSC(PCSetType(pc, settings.pc_type.c_str()));
    // Newton refactors with the same pattern many times: keep GAMG's interpolation and only
    // recompute the Galerkin products (-pc_gamg_reuse_interpolation false turns it off).
    if (settings.pc_type == "gamg") STIFFSOFT_PETSC(PCGAMGSetReuseInterpolation(pc, PETSC_TRUE));
  }
  if (settings.use_options_database) {
    STIFFSOFT_PETSC(KSPSetFromOptions(m.ksp));
    m.rtol_from_options = has_option("-ksp_rtol");
  }
  // The tolerance is on the true residual ‖b − Hp‖: CG can measure it directly, GMRES does
  // with right preconditioning; MINRES only has the preconditioned norm (then solve() refines).
  const std::string ksp = m.ksp_type();
  if (ksp == KSPCG && !has_option("-ksp_norm_type"))
    STIFFSOFT_PETSC(KSPSetNormType(m.ksp, KSP_NORM_UNPRECONDITIONED));
  if ((ksp == KSPGMRES || ksp == KSPFGMRES) && !has_option("-ksp_pc_side"))
    STIFFSOFT_PETSC(KSPSetPCSide(m.ksp, PC_RIGHT));
  // PETSc's own PCVPBJACOBI needs AIJ: -pc_type vpbjacobi on the command line means ours.
  if (m.pc_type() == PCVPBJACOBI && m.settings.matrix_type != "aij") use_block_jacobi_shell(m.pc());
  // ICC is sequential: in parallel, block Jacobi over the ranks with ICC inside each rank's
  // block (through the options database, where -sub_pc_type given by the user wins).
  bool parallel_icc = false;
  if (m.pc_type() == PCICC && m.size > 1) {
    STIFFSOFT_PETSC(PCSetType(m.pc(), PCBJACOBI));
    if (!has_option("-sub_pc_type")) STIFFSOFT_PETSC(PetscOptionsSetValue(nullptr, "-sub_pc_type", "icc"));
    parallel_icc = true;
  }
  m.shell = m.pc_type() == PCSHELL;
  // The preconditioner in use decides the default matrix type (the options may have changed it).
  if (m.shell)
    m.preconditioner = "vpbjacobi";
  else if (parallel_icc)
    m.preconditioner = "icc";
  else
    m.preconditioner = m.pc_type();
  if (m.rtol_from_options) {
    PetscReal rtol = 0;
    STIFFSOFT_PETSC(KSPGetTolerances(m.ksp, &rtol, nullptr, nullptr, nullptr));
    m.rtol = rtol;
  }
}

PetscSolver::~PetscSolver() {
  m_impl->destroy_matrix();
  if (PetscSession::running()) KSPDestroy(&m_impl->ksp);
}

void PetscSolver::set_block_sizes(const std::vector<int>& sizes) {
  for (const int s : sizes)
    if (s <= 0 || s % 3 != 0)
      throw std::invalid_argument("PETSc backend: DOF block size " + std::to_string(s) +
                                  "; expected a positive multiple of 3");
  if (m_impl->given_block_sizes != sizes) m_impl->pattern.reset();  // analyse again under the new sizes
  m_impl->given_block_sizes = sizes;
}

void PetscSolver::set_relative_tolerance(double eta) {
  check_relative_tolerance(eta);
  if (!m_impl->rtol_from_options) m_impl->rtol = eta;
}

int PetscSolver::preallocations() const { return m_impl->preallocations; }

std::pair<int, int> PetscSolver::owned_rows() const { return {m_impl->row_begin, m_impl->row_end}; }

std::string PetscSolver::name() const { return "petsc:" + m_impl->ksp_type() + ":" + m_impl->preconditioner; }

void PetscSolver::analyze_pattern(const Eigen::SparseMatrix<double>& upper) {
  Impl& m = *m_impl;
  const int n = int(upper.rows());
  if (n == 0 || n % 3 != 0 || upper.cols() != n)
    throw std::invalid_argument("PETSc backend: the matrix is " + std::to_string(upper.rows()) + " × " +
                                std::to_string(upper.cols()) +
                                "; expected square with a positive multiple of 3 rows");
  std::vector<int> sizes;
  if (!m.given_block_sizes.empty()) {
    long sum = 0;
    for (const int s : m.given_block_sizes) sum += s;
    if (sum != n)
      throw std::invalid_argument("PETSc backend: the DOF block sizes add up to " + std::to_string(sum) +
                                  " rows but the matrix has " + std::to_string(n));
    sizes = m.given_block_sizes;
  } else {
    sizes = infer_block_sizes(upper);
  }
  // The pattern analysed already (each time step starts a new Hessian, often of the last
  // step's pattern): the matrix, its preallocation and the preconditioner's symbolic set-up stay.
  if (m.pattern && m.n == n && sizes == m.block_sizes && m.pattern->same_pattern(upper)) return;
  m.block_sizes = std::move(sizes);
  m.in_place = Impl::InPlace::Unchecked;
  const std::vector<int> bounds = split_rows(m.block_sizes, m.size);
  m.n = n;
  m.row_begin = bounds[m.rank];
  m.row_end = bounds[m.rank + 1];
  const int local = m.row_end - m.row_begin;

  m.destroy_matrix();
  STIFFSOFT_PETSC(MatCreate(m.comm, &m.A));
  STIFFSOFT_PETSC(MatSetSizes(m.A, local, local, n, n));
  const std::string type =
      m.settings.matrix_type.empty() ? default_matrix_type(m.preconditioner) : m.settings.matrix_type;
  if (type != "baij" && type != "sbaij" && type != "aij")
    throw std::invalid_argument("PETSc backend: matrix type '" + type + "'; expected baij, sbaij or aij");
  STIFFSOFT_PETSC(MatSetType(m.A, type.c_str()));
  STIFFSOFT_PETSC(MatSetBlockSize(m.A, 3));
  if (m.settings.use_options_database) STIFFSOFT_PETSC(MatSetFromOptions(m.A));
  PetscBool symmetric_storage = PETSC_FALSE;
  STIFFSOFT_PETSC(PetscObjectTypeCompareAny((PetscObject)m.A, &symmetric_storage, MATSEQSBAIJ, MATMPISBAIJ,
                                            MATSBAIJ, ""));
  const BlockStorage storage = symmetric_storage ? BlockStorage::Upper : BlockStorage::Full;
  m.pattern.emplace(upper, storage, m.row_begin / 3, m.row_end / 3);

  std::vector<int> diagonal, off_diagonal;
  m.pattern->count_blocks(m.row_begin / 3, m.row_end / 3, diagonal, off_diagonal);
  STIFFSOFT_PETSC(MatXAIJSetPreallocation(m.A, 3, diagonal.data(), off_diagonal.data(), diagonal.data(),
                                          off_diagonal.data()));
  STIFFSOFT_PETSC(MatSetOption(m.A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  STIFFSOFT_PETSC(MatSetOption(m.A, MAT_ROW_ORIENTED, PETSC_FALSE));  // blocks are column-major
  STIFFSOFT_PETSC(MatSetOption(m.A, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
  STIFFSOFT_PETSC(MatSetOption(m.A, MAT_SYMMETRIC, PETSC_TRUE));
  STIFFSOFT_PETSC(MatSetOption(m.A, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  PetscBool mpibaij = PETSC_FALSE;  // PETSc 3.18's MPIBAIJ rejects MAT_SPD, a hint only
  STIFFSOFT_PETSC(PetscObjectTypeCompare((PetscObject)m.A, MATMPIBAIJ, &mpibaij));
  if (!mpibaij) STIFFSOFT_PETSC(MatSetOption(m.A, MAT_SPD, PETSC_TRUE));
  STIFFSOFT_PETSC(MatCreateVecs(m.A, &m.x, &m.b));
  STIFFSOFT_PETSC(VecDuplicate(m.x, &m.r));
  STIFFSOFT_PETSC(VecScatterCreateToAll(m.x, &m.to_all, &m.x_all));

  if (m.pc_type() == PCGAMG && m.settings.gamg_translations) m.set_translation_near_null_space();
  m.block_jacobi = std::make_unique<BlockJacobi>(m.block_sizes, m.row_begin, m.row_end);
  if (m.shell) STIFFSOFT_PETSC(PCShellSetContext(m.pc(), m.block_jacobi.get()));
  // The preconditioner of the old matrix (sizes, hierarchy) is stale: start the KSP afresh.
  STIFFSOFT_PETSC(KSPReset(m.ksp));
  ++m.preallocations;
  m.cholmod_analyzed = false;
}

void PetscSolver::analyze_blocks(const BlockUpper& H) {
  Impl& m = *m_impl;
  if (m.pattern && m.pattern->maps(H)) return;
  analyze_pattern(H.compressed());
  m.pattern->map_blocks(H);
}

bool PetscSolver::factorize(const Eigen::SparseMatrix<double>& upper) {
  const auto start = std::chrono::steady_clock::now();
  Impl& m = *m_impl;
  if (!m.pattern || !m.pattern->same_pattern(upper)) analyze_pattern(upper);
  m.pattern->gather_values(upper, m.values);
  if (m.settings.fallback == KrylovFallback::Cholmod && &upper != &m.upper) m.upper = upper;
  m.upper_current = true;
  return factorize_values(m.shell ? &upper : nullptr, false, start);
}

bool PetscSolver::factorize_blocks(const BlockUpper& H, double shift) {
  Impl& m = *m_impl;
  // Under MPI the fallback needs every rank's whole H, and the shell preconditioner reads the
  // compressed matrix: those take the compressed copy.
  if (m.size > 1 || m.shell) {
    if (m.settings.fallback != KrylovFallback::Cholmod) return factorize(H.compressed(shift));
    Eigen::SparseMatrix<double> upper = H.compressed(shift);
    m.upper.swap(upper);  // Eigen 3.4's sparse matrices copy on assignment, even from a temporary
    return factorize(m.upper);
  }
  const auto start = std::chrono::steady_clock::now();
  analyze_blocks(H);  // nothing to do for the blocks analysed last
  const bool in_petsc = m.in_place == Impl::InPlace::Yes;
  if (in_petsc) {
    m.with_petsc_values([&](PetscScalar* a) { m.pattern->gather_values(H, shift, a); });
    // Assembling nothing marks A changed (its state), so that the preconditioner is rebuilt.
    STIFFSOFT_PETSC(MatAssemblyBegin(m.A, MAT_FINAL_ASSEMBLY));
    STIFFSOFT_PETSC(MatAssemblyEnd(m.A, MAT_FINAL_ASSEMBLY));
  } else {
    m.values.resize(m.pattern->num_values());
    m.pattern->gather_values(H, shift, m.values.data());
  }
  m.upper_current = false;
  return factorize_values(nullptr, in_petsc, start);
}

bool PetscSolver::factorize_values(const Eigen::SparseMatrix<double>* upper, bool in_petsc,
                                   std::chrono::steady_clock::time_point start) {
  Impl& m = *m_impl;
  m_report = LinearSolveReport{};
  m_report.requested_tolerance = m.rtol;
  m.cholmod_ready = false;
  m.setup_failure.clear();
  if (!in_petsc) {
    const std::vector<int>& offsets = m.pattern->row_offsets();
    const std::vector<int>& columns = m.pattern->block_columns();
    for (int i = 0; i + m.pattern->row_begin() < m.pattern->row_end(); ++i) {
      const PetscInt I = m.pattern->row_begin() + i;
      const int count = offsets[i + 1] - offsets[i];
      STIFFSOFT_PETSC(MatSetValuesBlocked(m.A, 1, &I, count, columns.data() + offsets[i],
                                          m.values.data() + 9 * std::size_t(offsets[i]), INSERT_VALUES));
    }
    STIFFSOFT_PETSC(MatAssemblyBegin(m.A, MAT_FINAL_ASSEMBLY));
    STIFFSOFT_PETSC(MatAssemblyEnd(m.A, MAT_FINAL_ASSEMBLY));
    if (m.in_place == Impl::InPlace::Unchecked && m.size == 1)
      m.in_place = m.holds_values_in_place() ? Impl::InPlace::Yes : Impl::InPlace::No;
  }

  bool indefinite = false;
  if (m.shell) {
    int ok = m.block_jacobi->compute(*upper) ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_LAND, m.comm);
    if (!ok) {
      indefinite = true;
      m.setup_failure = "block Jacobi: a diagonal DOF block is not positive definite, so H is not either";
    }
  }
  if (m.setup_failure.empty()) {
    STIFFSOFT_PETSC(KSPSetOperators(m.ksp, m.A, m.A));
    STIFFSOFT_PETSC(KSPSetUp(m.ksp));
    m.pc_shift = 0;
    const int code = m.preconditioner_failure();
    if (code != int(PC_NOERROR) && !m.shift_preconditioner())
      m.setup_failure = std::string("preconditioner set-up failed: ") + PCFailedReasons[code];
  }
  bool ok = true;
  if (!m.setup_failure.empty()) {
    m_report.primary_failure = m.setup_failure;
    if (m.settings.fallback == KrylovFallback::Cholmod) {
      ok = m.factorize_fallback();
      m_report.fallback_used = true;
    } else {
      ok = false;
    }
    if (!ok) {
      // A non-SPD diagonal block, or CHOLMOD's failure, proves H indefinite; an ICC pivot alone does not.
      const bool proven = indefinite || m.settings.fallback == KrylovFallback::Cholmod;
      m_report.status = proven ? LinearSolveStatus::Indefinite : LinearSolveStatus::PreconditionerFailed;
      m_report.reason = m.setup_failure;
    }
  }
  m_report.setup_seconds = seconds_since(start);
  return ok;
}

Eigen::VectorXd PetscSolver::solve(const Eigen::VectorXd& rhs) {
  const auto start = std::chrono::steady_clock::now();
  Impl& m = *m_impl;
  if (!m.pattern || rhs.size() != m.n)
    throw std::invalid_argument("PETSc backend: solve() with a right-hand side of " +
                                std::to_string(rhs.size()) + " rows; expected " + std::to_string(m.n) +
                                " (after factorize())");
  const double setup = m_report.setup_seconds;
  const std::string primary = m_report.primary_failure;
  m_report = LinearSolveReport{};
  m_report.setup_seconds = setup;
  m_report.requested_tolerance = m.rtol;
  if (m.cholmod_ready) {  // the preconditioner failed in factorize(): the fallback solves
    Eigen::VectorXd p = m.cholmod_solve(rhs, primary, m_report);
    m_report.solve_seconds = seconds_since(start);
    return p;
  }

  PetscScalar* b = nullptr;
  STIFFSOFT_PETSC(VecGetArray(m.b, &b));
  std::copy(rhs.data() + m.row_begin, rhs.data() + m.row_end, b);
  STIFFSOFT_PETSC(VecRestoreArray(m.b, &b));
  PetscReal atol = 0, dtol = 0;
  PetscInt max_its = 0;
  STIFFSOFT_PETSC(KSPGetTolerances(m.ksp, nullptr, &atol, &dtol, &max_its));
  PetscReal b_norm = 0;
  STIFFSOFT_PETSC(VecNorm(m.b, NORM_2, &b_norm));

  auto true_residual = [&] {
    PetscReal r_norm = 0;
    STIFFSOFT_PETSC(MatMult(m.A, m.x, m.r));
    STIFFSOFT_PETSC(VecAYPX(m.r, -1.0, m.b));
    STIFFSOFT_PETSC(VecNorm(m.r, NORM_2, &r_norm));
    return b_norm > 0 ? double(r_norm / b_norm) : double(r_norm);
  };
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  double residual = 0;
  int iterations = 0;
  // Pass 0 from p = 0; further passes (at most 4) continue from p when the Krylov method's own
  // stopping test (a preconditioned norm for MINRES) was met but the true residual is still
  // above η, each with the tolerance cut by 10 η / residual.
  const auto krylov = [&] {
    double rtol = m.rtol;
    for (int pass = 0; pass < 5; ++pass) {
      STIFFSOFT_PETSC(KSPSetTolerances(m.ksp, rtol, atol, dtol, max_its));
      STIFFSOFT_PETSC(KSPSetInitialGuessNonzero(m.ksp, pass > 0 ? PETSC_TRUE : PETSC_FALSE));
      STIFFSOFT_PETSC(KSPSolve(m.ksp, m.b, m.x));
      PetscInt its = 0;
      STIFFSOFT_PETSC(KSPGetIterationNumber(m.ksp, &its));
      STIFFSOFT_PETSC(KSPGetConvergedReason(m.ksp, &reason));
      iterations += int(its);
      residual = true_residual();
      if (reason <= 0 || residual <= m.rtol || !std::isfinite(residual)) break;
      rtol = std::max(rtol * 0.1 * m.rtol / residual, 1e-15);
    }
  };
  krylov();
  // An ICC that came out indefinite (or failed when applied) is rebuilt shifted, and CG
  // starts again; the shift stays for the solves until the next factorize().
  while ((reason == KSP_DIVERGED_INDEFINITE_PC || reason == KSP_DIVERGED_PC_FAILED) && m.shift_preconditioner())
    krylov();
  m_report.iterations = iterations;
  m_report.relative_residual = residual;
  m_report.status = status_of(reason);
  m_report.reason = KSPConvergedReasons[reason];
  if (m_report.status == LinearSolveStatus::Converged && !(residual <= m.rtol)) {
    m_report.status = LinearSolveStatus::Diverged;
    m_report.reason += " but the true residual stayed above the tolerance";
  }
  if (m_report.status == LinearSolveStatus::Converged) {
    // For SPD H, bᵀp = bᵀH⁻¹b > 0 (p = −H⁻¹g is a descent direction). A converged solve that
    // breaks it (CG need not meet negative curvature, e.g. behind a shifted ICC) is refused.
    PetscScalar b_dot_p = 0;
    STIFFSOFT_PETSC(VecDot(m.b, m.x, &b_dot_p));
    if (!(b_dot_p > 0) && b_norm > 0) {
      m_report.status = LinearSolveStatus::Indefinite;
      m_report.reason += " but bᵀp ≤ 0: H is not positive definite";
    }
  }

  Eigen::VectorXd p(m.n);
  if (m_report.converged()) {
    STIFFSOFT_PETSC(VecScatterBegin(m.to_all, m.x, m.x_all, INSERT_VALUES, SCATTER_FORWARD));
    STIFFSOFT_PETSC(VecScatterEnd(m.to_all, m.x, m.x_all, INSERT_VALUES, SCATTER_FORWARD));
    const PetscScalar* all = nullptr;
    STIFFSOFT_PETSC(VecGetArrayRead(m.x_all, &all));
    std::copy(all, all + m.n, p.data());
    STIFFSOFT_PETSC(VecRestoreArrayRead(m.x_all, &all));
  } else if (m.settings.fallback == KrylovFallback::Cholmod) {
    const std::string failure = m_report.reason + " after " + std::to_string(iterations) +
                                " iterations (relative residual " + std::to_string(residual) + ")";
    p = m.cholmod_solve(rhs, failure, m_report);
  } else {
    p.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  m_report.solve_seconds = seconds_since(start);
  return p;
}

PetscSolverSettings default_petsc_method() {
  // CG with ICC(0) had the lowest set-up + solve time of the PETSc methods on every measured
  // system but the largest soft lattice at η = 1e-3 (GAMG); see docs/benchmarks.md.
  PetscSolverSettings s;
  s.ksp_type = "cg";
  s.pc_type = "icc";
  return s;
}

}  // namespace stiffsoft
