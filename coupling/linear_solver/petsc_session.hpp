#pragma once
/// @file PETSc (and MPI) initialisation, once per process: an RAII session for main(), and a
/// lazy start for code that needs PETSc when main did not create a session (tests, tools).

#include <string>
#include <vector>

namespace stiffsoft {

/// Owns PetscInitialize … PetscFinalize (which also starts and ends MPI when PETSc started it).
/// Create one at the top of main(), before anything parses the command line:
///
///     stiffsoft::PetscSession petsc(argc, argv);  // takes the PETSc options (-ksp_type cg, …)
///     CLI::App app{…};
///     CLI11_PARSE(app, petsc.program_argc(), petsc.program_argv());
///     …                                           // only PetscSession::rank() == 0 writes files
///
/// Every rank of `mpirun -n N` runs the whole program; PETSc backends distribute only the
/// linear solve. If PETSc is already running (started lazily), the options are added to its
/// database instead and this session does not finalise it.
class PetscSession {
 public:
  /// Starts PETSc with the PETSc options of argv (see split_petsc_arguments()); also reads
  /// the PETSC_OPTIONS environment variable and ~/.petscrc as PETSc always does.
  PetscSession(int argc, const char* const* argv);
  /// Starts PETSc with the given options (e.g. {"-ksp_monitor"}), no program arguments.
  explicit PetscSession(const std::vector<std::string>& options = {});
  /// PetscFinalize (and MPI_Finalize when PETSc started MPI), if this session started PETSc.
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;

  /// Number of the arguments left for the program (argv[0] included).
  int program_argc() const { return int(m_program_pointers.size()) - 1; }
  /// The arguments left for the program, argv-style (null-terminated), valid while the session lives.
  char** program_argv() { return m_program_pointers.data(); }
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
  std::vector<std::string> m_petsc, m_program;
  std::vector<char*> m_petsc_pointers, m_program_pointers;
  bool m_owns = false;
};

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
