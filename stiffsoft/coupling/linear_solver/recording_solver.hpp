#pragma once
/// @file A LinearSolver that passes everything to another backend and hands every system it
/// solves to a callback: how tools capture the Hessians of a running simulation (register it
/// with register_linear_solver() and name it in SimulationSettings::linear_solver).

#include <functional>
#include <memory>

#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>

namespace stiffsoft {

/// Wraps `inner`; after each solve() calls sink(H's upper triangle, b).
class RecordingSolver final : public LinearSolver {
 public:
  /// What receives each solved system.
  using Sink = std::function<void(const Eigen::SparseMatrix<double>& upper, const Eigen::VectorXd& b)>;
  /// Records the systems `inner` solves.
  RecordingSolver(std::unique_ptr<LinearSolver> inner, Sink sink);
  /// See LinearSolver.
  void analyze_pattern(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver; keeps a copy of H for the sink.
  bool factorize(const Eigen::SparseMatrix<double>& upper) override;
  /// See LinearSolver; then calls the sink.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override;
  /// "record+" and the inner backend's name.
  std::string name() const override { return "record+" + m_inner->name(); }
  /// Passed on.
  void set_relative_tolerance(double eta) override { m_inner->set_relative_tolerance(eta); }
  /// The inner backend's.
  bool is_iterative() const override { return m_inner->is_iterative(); }
  /// Passed on.
  void set_block_sizes(const std::vector<int>& sizes) override { m_inner->set_block_sizes(sizes); }
  LinearSolverMemory memory() const override { return m_inner->memory(); }
  void restore_memory(const LinearSolverMemory& memory) override { m_inner->restore_memory(memory); }

 private:
  std::unique_ptr<LinearSolver> m_inner;
  Sink m_sink;
  Eigen::SparseMatrix<double> m_upper;
};

}  // namespace stiffsoft
