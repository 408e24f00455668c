#include <map>
#include <sstream>
#include <stdexcept>

#include <stiffsoft/coupling/linear_solver/auto_solver.hpp>
#include <stiffsoft/coupling/linear_solver/block_cholesky_solver.hpp>
#include <stiffsoft/coupling/linear_solver/cholmod_solver.hpp>
#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>
#include <stiffsoft/coupling/linear_solver/petsc_solver.hpp>

namespace stiffsoft {

namespace {

std::map<std::string, std::function<std::unique_ptr<LinearSolver>()>>& registry() {
  static std::map<std::string, std::function<std::unique_ptr<LinearSolver>()>> r;
  return r;
}

bool is_built_in(const std::string& name) {
  return name == "cholmod" || name == "block_cholesky" || name == "block_cg" || name == "auto" || name == "petsc" ||
         name.rfind("petsc:", 0) == 0;
}

std::vector<std::string> split(const std::string& s, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(s);
  for (std::string part; std::getline(in, part, separator);) parts.push_back(part);
  if (!s.empty() && s.back() == separator) parts.push_back("");
  return parts;
}

/// The PETSc settings a "petsc…" name stands for; throws std::invalid_argument for a bad one.
PetscSolverSettings petsc_settings(const std::string& name) {
  PetscSolverSettings settings = default_petsc_method();
  if (name == "petsc") return settings;
  const std::vector<std::string> parts = split(name, ':');
  if (parts.size() > 3 || parts[1].empty() || (parts.size() == 3 && parts[2].empty()))
    throw std::invalid_argument("linear solver '" + name +
                                "': expected petsc:KSP or petsc:KSP:PC, e.g. petsc:cg:gamg");
  settings.ksp_type = parts[1];
  if (parts.size() == 3) settings.pc_type = parts[2];
  check_petsc_method(settings);
  return settings;
}

[[noreturn]] void unknown(const std::string& name) {
  std::string names;
  for (const std::string& n : linear_solver_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown linear solver '" + name + "' (available: " + names + ")");
}

}  // namespace

const char* to_string(LinearSolveStatus status) {
  switch (status) {
    case LinearSolveStatus::NotSolved:
      return "not solved";
    case LinearSolveStatus::Converged:
      return "converged";
    case LinearSolveStatus::Indefinite:
      return "indefinite";
    case LinearSolveStatus::PreconditionerFailed:
      return "preconditioner failed";
    case LinearSolveStatus::IterationCap:
      return "iteration cap";
    case LinearSolveStatus::Diverged:
      return "diverged";
  }
  return "unknown";
}

void check_linear_solver_name(const std::string& name) {
  if (name == "cholmod" || name == "block_cholesky" || name == "block_cg" || name == "auto" || registry().count(name))
    return;
  if (name == "petsc" || name.rfind("petsc:", 0) == 0) {
    petsc_settings(name);
    return;
  }
  unknown(name);
}

std::unique_ptr<LinearSolver> make_linear_solver(const std::string& name) {
  if (name == "cholmod") return std::make_unique<CholmodSolver>();
  if (name == "block_cholesky") return std::make_unique<BlockCholeskySolver>();
  if (name == "block_cg") return std::make_unique<BlockCholeskySolver>(BlockCholesky::Fill::None);
  if (name == "auto") return std::make_unique<AutoSolver>();
  if (name == "petsc" || name.rfind("petsc:", 0) == 0)
    return std::make_unique<PetscSolver>(petsc_settings(name));
  if (const auto it = registry().find(name); it != registry().end()) return it->second();
  unknown(name);
}

void register_linear_solver(const std::string& name, std::function<std::unique_ptr<LinearSolver>()> factory) {
  if (is_built_in(name))
    throw std::invalid_argument("register_linear_solver: '" + name + "' is a built-in name");
  registry()[name] = std::move(factory);
}

std::vector<std::string> linear_solver_names() {
  std::vector<std::string> names{"cholmod", "auto", "petsc",
                                 "petsc:KSP[:PC] (KSP: cg, minres, gmres; PC: none, "
                                 "jacobi, pbjacobi, vpbjacobi, icc, gamg, hypre)",
                                 "block_cholesky", "block_cg"};
  for (const auto& [name, factory] : registry()) names.push_back(name);
  return names;
}

}  // namespace stiffsoft
