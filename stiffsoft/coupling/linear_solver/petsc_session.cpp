#include <stiffsoft/coupling/linear_solver/petsc_session.hpp>

#include <petscsys.h>

#include <memory>
#include <stdexcept>
#include <string>


namespace stiffsoft {

std::vector<char*> argv_pointers(std::vector<std::string>& strings) {
  std::vector<char*> p;
  for (std::string& s : strings) p.push_back(s.data());
  p.push_back(nullptr);
  return p;
}

PetscSession::PetscSession(const std::vector<std::string>& options, const std::string& program) {
  m_petsc.push_back(program);
  m_petsc.insert(m_petsc.end(), options.begin(), options.end());
  start();
}

void PetscSession::start() {
  m_petsc_pointers = argv_pointers(m_petsc);
  PetscBool finalized = PETSC_FALSE;
  PetscFinalized(&finalized);
  if (finalized)
    throw std::runtime_error("PetscSession: PETSc was already finalised in this process; it cannot restart");
  int argc = int(m_petsc.size());
  char** argv = m_petsc_pointers.data();
  if (running()) {
    if (argc > 1 && PetscOptionsInsertArgs(nullptr, argc - 1, argv + 1) != 0)
      throw std::runtime_error("PetscSession: PETSc rejected the options on the command line");
    return;
  }
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0)
    throw std::runtime_error("PetscSession: PetscInitialize failed (see PETSc's message above)");
  m_owns = true;
}

PetscSession::~PetscSession() {
  if (m_owns && running()) PetscFinalize();
}

bool PetscSession::running() {
  PetscBool initialized = PETSC_FALSE, finalized = PETSC_FALSE;
  PetscInitialized(&initialized);
  PetscFinalized(&finalized);
  return initialized && !finalized;
}

int PetscSession::rank() {
  if (!running()) return 0;
  PetscMPIInt r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

int PetscSession::size() {
  if (!running()) return 1;
  PetscMPIInt s = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}

void set_petsc_option(const std::string& name, const std::string& value) {
  ensure_petsc_initialized();
  if (PetscOptionsSetValue(nullptr, name.c_str(), value.empty() ? nullptr : value.c_str()) != 0)
    throw std::runtime_error("set_petsc_option: PETSc rejected " + name + " " + value);
}

void clear_petsc_option(const std::string& name) {
  if (PetscSession::running()) PetscOptionsClearValue(nullptr, name.c_str());
}

void ensure_petsc_initialized() {
  // A function-local static: destroyed (PetscFinalize) at exit, after main's objects.
  static std::unique_ptr<PetscSession> lazy;
  if (PetscSession::running()) return;
  if (lazy) throw std::runtime_error("ensure_petsc_initialized: PETSc was finalised; it cannot restart");
  lazy = std::make_unique<PetscSession>();
}

}  // namespace stiffsoft
