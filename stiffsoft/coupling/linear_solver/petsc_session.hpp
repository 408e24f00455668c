#pragma once
/// @file PETSc (and MPI) initialisation, once per process: an RAII session for main(), and a
/// lazy start for code that needs PETSc when main did not create a session (tests, tools).

#include <string>
#include <vector>

namespace stiffsoft {

/// Owns PetscInitialize … PetscFinalize (which also starts and ends MPI when PETSc started it).
/// A program creates one at the top of main(); the `stiffsoft` command does so through
/// apps/cli/petsc_command_line.hpp, which first takes PETSc's options (-ksp_type cg, …) out of
/// argv. Only PetscSession::rank() == 0 writes files.
///
/// Every rank of `mpirun -n N` runs the whole program; PETSc backends distribute only the
/// linear solve. If PETSc is already running (started lazily), the options are added to its
/// database instead and this session does not finalise it.
class PetscSession {
 public:
  /// Starts PETSc with the given options (e.g. {"-ksp_monitor"}) as the command line of
  /// `program` (PETSc's argv[0], shown by -log_view); also reads the PETSC_OPTIONS environment
  /// variable and ~/.petscrc as PETSc always does.
  explicit PetscSession(const std::vector<std::string>& options = {}, const std::string& program = "stiffsoft");
  /// PetscFinalize (and MPI_Finalize when PETSc started MPI), if this session started PETSc.
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;

  /// The arguments given to PETSc (argv[0] first).
  const std::vector<std::string>& petsc_arguments() const { return m_petsc; }
  /// True when this session called PetscInitialize (and will call PetscFinalize).
  bool owns_petsc() const { return m_owns; }

  /// Rank of this process in PETSC_COMM_WORLD; 0 when PETSc is not running.
  static int rank();
  /// Number of processes in PETSC_COMM_WORLD; 1 when PETSc is not running.
  static int size();
  /// True while PETSc is initialised and not finalised.
  static bool running();

 private:
  void start();
  std::vector<std::string> m_petsc;
  std::vector<char*> m_petsc_pointers;
  bool m_owns = false;
};

/// argv-style pointers to `strings` (null-terminated), valid while `strings` is unchanged.
std::vector<char*> argv_pointers(std::vector<std::string>& strings);

/// Sets `name` (e.g. "-ksp_monitor") in PETSc's options database, with an optional value;
/// objects created afterwards see it. Starts PETSc if needed.
void set_petsc_option(const std::string& name, const std::string& value = "");

/// Removes `name` from PETSc's options database (no-op when absent or PETSc is not running).
void clear_petsc_option(const std::string& name);

/// Starts PETSc without options (beyond PETSC_OPTIONS / ~/.petscrc) if it is not running, and
/// finalises it at process exit; does nothing when a PetscSession (or anything else) started it.
/// Throws std::runtime_error when PETSc was already finalised (MPI cannot restart).
void ensure_petsc_initialized();

}  // namespace stiffsoft
