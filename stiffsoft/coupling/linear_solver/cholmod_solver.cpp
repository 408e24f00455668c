#include <stiffsoft/coupling/linear_solver/cholmod_solver.hpp>

#include <omp.h>

#include <Eigen/CholmodSupport>
#include <chrono>
#include <limits>

#include <stiffsoft/coupling/linear_solver/refined_solve.hpp>

namespace stiffsoft {

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
/// Debian's CHOLMOD is compiled with CHOLMOD_OMP_NUM_THREADS = 4: every supernode loop of the
/// numeric factorisation asks OpenMP for 4 threads, whatever the machine and whatever the
/// simulation's thread count. On small factors the team's start and barriers cost more than
/// the arithmetic (measured: most of the solve time of the `light` pile on 2 cores), and on a
/// machine with fewer cores the threads oversubscribe it. So factors below this many flops
/// run on the calling thread (the parallel regions are made inactive), larger ones with
/// OpenMP's dynamic adjustment (no more threads than idle cores).
constexpr double kSerialFactorFlops = 5e7;

/// Sets the OpenMP controls for one factorisation and restores them afterwards.
class OpenMpScope {
 public:
  explicit OpenMpScope(double flops) : m_levels(omp_get_max_active_levels()), m_dynamic(omp_get_dynamic()) {
    if (flops < kSerialFactorFlops)
      omp_set_max_active_levels(0);
    else
      omp_set_dynamic(1);
  }
  ~OpenMpScope() {
    omp_set_max_active_levels(m_levels);
    omp_set_dynamic(m_dynamic);
  }
  OpenMpScope(const OpenMpScope&) = delete;
  OpenMpScope& operator=(const OpenMpScope&) = delete;

 private:
  int m_levels, m_dynamic;
};

/// CHOLMOD's LLᵀ, supernodal or simplicial as its analysis chooses (CholmodAuto: supernodal
/// when the factorisation's flops per factor entry reach Common->supernodal_switch, 40), with
/// simplicial factors computed as LLᵀ too (not CHOLMOD's default LDLᵀ), so that a
/// non-positive pivot fails the factorisation as it does in the supernodal one.
class Factorisation : public Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Upper> {
 public:
  Factorisation() {
    setMode(Eigen::CholmodAuto);
    cholmod().final_asis = 0;
    cholmod().final_ll = 1;
  }
  /// Whether the last analysis chose the supernodal method.
  bool supernodal() const { return m_cholmodFactor && m_cholmodFactor->is_super; }
};

}  // namespace

struct CholmodSolver::Impl {
  Factorisation llt;
  double flops = 0, nonzeros = 0;     // predicted by the last analysis
  Eigen::SparseMatrix<double> upper;  // the factorised H, for the residual
  bool factorized = false;
};

CholmodSolver::CholmodSolver() : m_impl(std::make_unique<Impl>()) {
  // CHOLMOD prints its warnings ("not positive definite") to stdout itself; here they are
  // statuses in the LinearSolveReport, which the caller logs.
  m_impl->llt.cholmod().print = 0;
}
CholmodSolver::~CholmodSolver() = default;

void CholmodSolver::analyze_pattern(const Eigen::SparseMatrix<double>& upper) {
  m_impl->llt.analyzePattern(upper);
  m_impl->flops = m_impl->llt.cholmod().fl;
  m_impl->nonzeros = m_impl->llt.cholmod().lnz;
}

double CholmodSolver::factor_flops() const { return m_impl->flops; }

double CholmodSolver::factor_nonzeros() const { return m_impl->nonzeros; }

bool CholmodSolver::supernodal() const { return m_impl->llt.supernodal(); }

bool CholmodSolver::factorize(const Eigen::SparseMatrix<double>& upper) {
  const auto start = std::chrono::steady_clock::now();
  m_report = LinearSolveReport{};
  {
    const OpenMpScope threads(m_impl->flops);
    m_impl->llt.factorize(upper);
  }
  m_impl->factorized = m_impl->llt.info() == Eigen::Success;
  if (m_impl->factorized) {
    m_impl->upper = upper;
  } else {
    m_report.status = LinearSolveStatus::Indefinite;
    m_report.reason = "CHOLMOD: the matrix is not positive definite";
  }
  m_report.setup_seconds = seconds_since(start);
  return m_impl->factorized;
}

Eigen::VectorXd CholmodSolver::solve(const Eigen::VectorXd& b) {
  const auto start = std::chrono::steady_clock::now();
  const int n = int(b.size());
  if (!m_impl->factorized) {
    m_report.status = LinearSolveStatus::Indefinite;
    return Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  }
  const auto H = m_impl->upper.selfadjointView<Eigen::Upper>();
  Eigen::VectorXd p = refined_solve(
      [&](const Eigen::VectorXd& x) { return Eigen::VectorXd(H * x); }, b, [&](const Eigen::VectorXd& rhs) { return Eigen::VectorXd(m_impl->llt.solve(rhs)); }, "CHOLMOD",
      m_report);
  if (m_impl->llt.info() != Eigen::Success && m_report.converged()) {
    m_report.status = LinearSolveStatus::Diverged;
    m_report.reason = "CHOLMOD: the solution is not finite";
    p.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  m_report.solve_seconds = seconds_since(start);
  return p;
}

}  // namespace stiffsoft
