#pragma once
/// @file main()'s PETSc session from the command line: PETSc's options go to PETSc, the rest to
/// the program's own parser (CLI11).

#include <optional>
#include <string>
#include <vector>

#include <stiffsoft/coupling/linear_solver/petsc_session.hpp>

#include "apps/cli/petsc_arguments.hpp"

namespace stiffsoft {

/// Splits argv (split_petsc_arguments()) and starts PETSc with its half when there is one, or
/// when an MPI launcher started the process (every rank must join MPI at once). Otherwise PETSc
/// starts on first use (ensure_petsc_initialized()), so that a run without a PETSc solver, and
/// `--help`, skip MPI's start (0.4 s of `stiffsoft --version`'s 0.65 s). Create one at the top
/// of main(), before anything parses the command line:
///
///     stiffsoft::PetscCommandLine petsc(argc, argv);  // takes -ksp_type cg, -log_view, …
///     CLI::App app{…};
///     CLI11_PARSE(app, petsc.program_argc(), petsc.program_argv());
class PetscCommandLine {
 public:
  /// Starts PETSc with the PETSc options of argv (argv[0] as PETSc's program name) if there
  /// are any or an MPI launcher started the process.
  PetscCommandLine(int argc, const char* const* argv);
  PetscCommandLine(const PetscCommandLine&) = delete;
  PetscCommandLine& operator=(const PetscCommandLine&) = delete;

  /// Number of the arguments left for the program (argv[0] included).
  int program_argc() const { return int(m_program_pointers.size()) - 1; }
  /// The arguments left for the program, argv-style (null-terminated), valid while this lives.
  char** program_argv() { return m_program_pointers.data(); }

 private:
  SplitCommandLine m_split;
  std::vector<char*> m_program_pointers;
  std::optional<PetscSession> m_session;  ///< empty: PETSc starts on first use
};

}  // namespace stiffsoft
