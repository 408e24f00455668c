#include <stiffsoft/coupling/linear_solver/recording_solver.hpp>

namespace stiffsoft {

RecordingSolver::RecordingSolver(std::unique_ptr<LinearSolver> inner, Sink sink)
    : m_inner(std::move(inner)), m_sink(std::move(sink)) {}

void RecordingSolver::analyze_pattern(const Eigen::SparseMatrix<double>& upper) {
  m_inner->analyze_pattern(upper);
}

bool RecordingSolver::factorize(const Eigen::SparseMatrix<double>& upper) {
  m_upper = upper;
  const bool ok = m_inner->factorize(upper);
  m_report = m_inner->last_report();
  return ok;
}

Eigen::VectorXd RecordingSolver::solve(const Eigen::VectorXd& b) {
  Eigen::VectorXd p = m_inner->solve(b);
  m_report = m_inner->last_report();
  m_sink(m_upper, b);
  return p;
}

}  // namespace stiffsoft
