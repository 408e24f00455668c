#pragma once
/// @file CHOLMOD supernodal Cholesky (SuiteSparse) behind the LinearSolver interface.

#include <memory>

#include "coupling/linear_solver/linear_solver.hpp"

namespace stiffsoft {

/// Direct sparse Cholesky H = L Lᵀ with CHOLMOD's supernodal method (through Eigen's wrapper).
class CholmodSolver final : public LinearSolver {
 public:
  CholmodSolver();
  ~CholmodSolver() override;
  void analyze_pattern(const Eigen::SparseMatrix<double>& upper) override;
  bool factorize(const Eigen::SparseMatrix<double>& upper) override;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override;
  std::string name() const override { return "cholmod"; }

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace stiffsoft
