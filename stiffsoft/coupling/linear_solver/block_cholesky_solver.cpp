#include <stiffsoft/coupling/linear_solver/block_cholesky_solver.hpp>

#include <chrono>
#include <limits>
#include <numeric>
#include <string>

#include <stiffsoft/coupling/linear_solver/block_sparse_pattern.hpp>
#include <stiffsoft/coupling/linear_solver/conjugate_gradients.hpp>
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
    m_report.reason = name() + ": a pivot block is not positive definite";
  }
  m_report.setup_seconds = seconds_since(start);
  return m_factorized;
}

bool BlockCholeskySolver::factorize(const Eigen::SparseMatrix<double>& upper) {
  return timed_factorize([&] {
    if (!m_factor.analysed()) analyze_pattern(upper);
    return factorize_with_boost([&](double boost) { return m_factor.factorize(upper, boost); });
  });
}

template <class Factor>
bool BlockCholeskySolver::factorize_with_boost(Factor&& factor) {
  if (factor(0.0)) return true;
  if (!m_krylov) return false;
  for (double boost = 1e-3; boost <= 1; boost *= 10)
    if (factor(boost)) return true;
  return false;
}

void BlockCholeskySolver::analyze_blocks(const BlockUpper& H) { m_factor.analyze(H); }

bool BlockCholeskySolver::factorize_blocks(const BlockUpper& H, double shift) {
  return timed_factorize([&] {
    if (!m_factor.analysed()) m_factor.analyze(H);
    return factorize_with_boost([&](double boost) { return m_factor.factorize(H, shift, boost); });
  });
}

Eigen::VectorXd BlockCholeskySolver::solve(const Eigen::VectorXd& b) {
  const auto start = std::chrono::steady_clock::now();
  if (!m_factorized) {
    m_report.status = LinearSolveStatus::Indefinite;
    return Eigen::VectorXd::Constant(b.size(), std::numeric_limits<double>::quiet_NaN());
  }
  const auto multiply = [&](const Eigen::VectorXd& x) { return m_factor.multiply(x); };
  const auto factor_solve = [&](const Eigen::VectorXd& rhs) { return m_factor.solve(rhs); };
  Eigen::VectorXd p = m_krylov ? conjugate_gradients(multiply, factor_solve, b, m_eta, kKrylovIterationCap, name(), m_report)
                               : refined_solve(multiply, b, factor_solve, name(), m_report);
  if (m_krylov && !m_report.converged()) p = fallback_solve(b);
  m_report.solve_seconds = seconds_since(start);
  return p;
}

Eigen::VectorXd BlockCholeskySolver::fallback_solve(const Eigen::VectorXd& b) {
  const std::string failure = m_report.reason + " after " + std::to_string(m_report.iterations) + " iterations";
  if (!m_fallback) m_fallback = std::make_unique<BlockCholesky>();
  const int iterations = m_report.iterations;
  m_fallback->analyze(m_factor.factorised());
  Eigen::VectorXd p;
  if (m_fallback->factorize(m_factor.factorised(), m_factor.shift())) {
    p = refined_solve([&](const Eigen::VectorXd& x) { return m_fallback->multiply(x); }, b,
                      [&](const Eigen::VectorXd& rhs) { return m_fallback->solve(rhs); }, "block_cholesky", m_report);
  } else {
    p = Eigen::VectorXd::Constant(b.size(), std::numeric_limits<double>::quiet_NaN());
    m_report.status = LinearSolveStatus::Indefinite;
    m_report.reason = "block_cholesky: a pivot block is not positive definite";
  }
  m_report.iterations = iterations;
  m_report.fallback_used = true;
  m_report.primary_failure = failure;
  return p;
}

}  // namespace stiffsoft
