#include "coupling/linear_solver/cholmod_solver.hpp"

#include <Eigen/CholmodSupport>
#include <stdexcept>

namespace stiffsoft {

struct CholmodSolver::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Upper> llt;
};

CholmodSolver::CholmodSolver() : m_impl(std::make_unique<Impl>()) {}
CholmodSolver::~CholmodSolver() = default;

void CholmodSolver::analyze_pattern(const Eigen::SparseMatrix<double>& upper) {
  m_impl->llt.analyzePattern(upper);
}

bool CholmodSolver::factorize(const Eigen::SparseMatrix<double>& upper) {
  m_impl->llt.factorize(upper);
  return m_impl->llt.info() == Eigen::Success;
}

Eigen::VectorXd CholmodSolver::solve(const Eigen::VectorXd& b) { return m_impl->llt.solve(b); }

std::unique_ptr<LinearSolver> make_linear_solver(const std::string& name) {
  if (name == "cholmod") return std::make_unique<CholmodSolver>();
  throw std::invalid_argument("unknown linear solver '" + name + "' (available: cholmod)");
}

}  // namespace stiffsoft
