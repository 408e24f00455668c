#include <stiffsoft/coupling/linear_solver/auto_solver.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <stiffsoft/coupling/linear_solver/block_cholesky_solver.hpp>
#include <stiffsoft/coupling/linear_solver/cholmod_solver.hpp>
#include <stiffsoft/coupling/linear_solver/petsc_solver.hpp>

namespace stiffsoft {

AutoSolver::AutoSolver() = default;
AutoSolver::~AutoSolver() = default;

void AutoSolver::analyze_pattern(const Eigen::SparseMatrix<double>& upper) {
  choose(long(upper.nonZeros()), int(upper.rows()), [&](LinearSolver& s) { s.analyze_pattern(upper); });
}

void AutoSolver::analyze_blocks(const BlockUpper& H) {
  choose(H.upper_nonzeros(), H.num_dofs(), [&](LinearSolver& s) { s.analyze_blocks(H); });
}

bool AutoSolver::affine_bodies_only(int rows) const {
  return !m_block_sizes.empty() && std::accumulate(m_block_sizes.begin(), m_block_sizes.end(), 0) == rows &&
         std::all_of(m_block_sizes.begin(), m_block_sizes.end(), [](int s) { return s == 12; });
}

std::unique_ptr<LinearSolver> AutoSolver::make_backend(bool krylov, int rows) const {
  const bool blocks = affine_bodies_only(rows);
  std::unique_ptr<LinearSolver> backend;
  if (krylov && blocks)
    backend = std::make_unique<BlockCholeskySolver>(BlockCholesky::Fill::None);
  else if (krylov)
    backend = std::make_unique<PetscSolver>(default_petsc_method());
  else if (blocks)
    backend = std::make_unique<BlockCholeskySolver>();
  else
    backend = std::make_unique<CholmodSolver>();
  if (krylov && m_eta > 0) backend->set_relative_tolerance(m_eta);
  if (!m_block_sizes.empty()) backend->set_block_sizes(m_block_sizes);
  return backend;
}

void AutoSolver::choose(long nonzeros, int rows, const std::function<void(LinearSolver&)>& analyse) {
  // A choice without a backend was given back by restore_memory(): a resumed run's, as it was.
  if (!m_backend && m_choice.decided_nonzeros >= 0) m_backend = make_backend(m_choice.krylov, rows);
  const bool redecide = !m_backend || std::abs(nonzeros - m_choice.decided_nonzeros) >
                                          kAutoRedecideChange * double(m_choice.decided_nonzeros);
  if (!redecide) {
    analyse(*m_backend);
    return;
  }
  // Above kAutoKrylovRows only the block Cholesky is asked, and not again once it has given way
  // to block_cg while the pattern grows: its prediction grows with it (its analysis of a
  // 5,066-cube pile took 0.4–0.6 s).
  const bool grown_past_direct = m_backend && m_choice.krylov && nonzeros > m_choice.decided_nonzeros;
  m_choice.decided_nonzeros = nonzeros;
  if (rows < kAutoKrylovRows || (affine_bodies_only(rows) && !grown_past_direct)) {
    std::unique_ptr<LinearSolver> direct = make_backend(false, rows);
    analyse(*direct);
    double flops = 0, bound = kAutoCholmodFlops;
    if (auto* blocks = dynamic_cast<BlockCholeskySolver*>(direct.get())) {
      bound = kAutoBlockCholeskyFlops;
      flops = blocks->factor_flops();
    } else {
      flops = static_cast<CholmodSolver&>(*direct).factor_flops();
    }
    if (flops <= bound) {
      m_backend = std::move(direct);  // analysed already
      m_choice.krylov = false;
      return;
    }
  }
  if (!m_choice.krylov || !m_backend) {
    m_backend = make_backend(true, rows);
    m_choice.krylov = true;
  }
  analyse(*m_backend);
}

LinearSolverMemory AutoSolver::memory() const { return m_choice; }

void AutoSolver::restore_memory(const LinearSolverMemory& memory) {
  m_backend.reset();
  m_choice = memory;
}

bool AutoSolver::factorize(const Eigen::SparseMatrix<double>& upper) {
  if (!m_backend) analyze_pattern(upper);
  const bool ok = m_backend->factorize(upper);
  m_report = m_backend->last_report();
  return ok;
}

bool AutoSolver::factorize_blocks(const BlockUpper& H, double shift) {
  if (!m_backend) analyze_blocks(H);
  const bool ok = m_backend->factorize_blocks(H, shift);
  m_report = m_backend->last_report();
  return ok;
}

Eigen::VectorXd AutoSolver::solve(const Eigen::VectorXd& b) {
  if (!m_backend) throw std::logic_error("AutoSolver::solve before factorize");
  Eigen::VectorXd p = m_backend->solve(b);
  m_report = m_backend->last_report();
  return p;
}

std::string AutoSolver::name() const { return m_backend ? "auto→" + m_backend->name() : "auto"; }

void AutoSolver::set_relative_tolerance(double eta) {
  m_eta = eta;
  if (m_backend) m_backend->set_relative_tolerance(eta);
}

bool AutoSolver::is_iterative() const { return m_backend && m_backend->is_iterative(); }

void AutoSolver::set_block_sizes(const std::vector<int>& sizes) {
  m_block_sizes = sizes;
  if (m_backend) m_backend->set_block_sizes(sizes);
}

}  // namespace stiffsoft
