#include <stiffsoft/coupling/linear_solver/block_cholesky_solver.hpp>

#include <chrono>
#include <limits>
#include <numeric>

#include <stiffsoft/coupling/linear_solver/block_sparse_pattern.hpp>
#include <stiffsoft/coupling/linear_solver/refined_solve.hpp>

namespace stiffsoft {

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

void BlockCholeskySolver::analyze_pattern(const Eigen::SparseMatrix<double>& upper) {
  const bool given = std::accumulate(m_sizes.begin(), m_sizes.end(), 0) == upper.rows() && !m_sizes.empty();
  m_factor.analyze(upper, given ? m_sizes : infer_block_sizes(upper));
}

template <class Factorize>
bool BlockCholeskySolver::timed_factorize(Factorize&& factorize) {
  const auto start = std::chrono::steady_clock::now();
  m_report = LinearSolveReport{};
  m_factorized = factorize();
  if (!m_factorized) {
    m_report.status = LinearSolveStatus::Indefinite;
    m_report.reason = "block Cholesky: a pivot block is not positive definite";
  }
  m_report.setup_seconds = seconds_since(start);
  return m_factorized;
}

bool BlockCholeskySolver::factorize(const Eigen::SparseMatrix<double>& upper) {
  return timed_factorize([&] {
    if (!m_factor.analysed()) analyze_pattern(upper);
    return m_factor.factorize(upper);
  });
}

void BlockCholeskySolver::analyze_blocks(const BlockUpper& H) { m_factor.analyze(H); }

bool BlockCholeskySolver::factorize_blocks(const BlockUpper& H, double shift) {
  return timed_factorize([&] {
    if (!m_factor.analysed()) m_factor.analyze(H);
    return m_factor.factorize(H, shift);
  });
}

Eigen::VectorXd BlockCholeskySolver::solve(const Eigen::VectorXd& b) {
  const auto start = std::chrono::steady_clock::now();
  if (!m_factorized) {
    m_report.status = LinearSolveStatus::Indefinite;
    return Eigen::VectorXd::Constant(b.size(), std::numeric_limits<double>::quiet_NaN());
  }
  Eigen::VectorXd p = refined_solve([&](const Eigen::VectorXd& x) { return m_factor.multiply(x); }, b,
                                    [&](const Eigen::VectorXd& rhs) { return m_factor.solve(rhs); }, "block Cholesky",
                                    m_report);
  m_report.solve_seconds = seconds_since(start);
  return p;
}

}  // namespace stiffsoft
