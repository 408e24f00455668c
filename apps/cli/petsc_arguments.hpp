#pragma once
/// @file Splitting a command line between PETSc's options database and the program's own
/// parser (CLI11): `stiffsoft run scene.json -o out -ksp_type cg -pc_type gamg -log_view`.

#include <string>
#include <string_view>
#include <vector>

namespace stiffsoft {

/// A command line split in two, each half starting with the program name argv[0].
struct SplitCommandLine {
  std::vector<std::string> petsc;    ///< argv[0], then the PETSc options with their values, in order
  std::vector<std::string> program;  ///< argv[0], then every other argument, in order (for CLI11)
};

/// True for an argument that belongs to PETSc: it starts with -ksp_, -pc_, -mat_, -vec_,
/// -log_, -options_, -malloc, -sub_, -info, or is -log_view, -help_petsc, -on_error_abort,
/// -no_signal_handler, -fp_trap, -memory_view. (Single dash; the program's options use "--" or
/// one-letter short forms, so nothing collides.)
bool is_petsc_option(std::string_view argument);

/// Splits argv. A PETSc option takes the next argument as its value when that does not start
/// with '-' (or is a number such as -1e-3), except for PETSc's flags with an optional value
/// (names with "monitor", "view", "converged_reason", "options_left", -info, -malloc_…,
/// -help_petsc, …): those take it only when it looks like a viewer or a boolean ("ascii",
/// ":file.txt", "ascii:log.txt", "true", "0", …), so `-log_view run scene.json` keeps `run`
/// for the program. `-help_petsc` is passed to PETSc as `-help` (plain `-help`/`--help` stay
/// the program's).
SplitCommandLine split_petsc_arguments(int argc, const char* const* argv);

/// True for an environment entry ("NAME=value" or "NAME") that an MPI launcher or an MPI
/// singleton sets (OMPI_*, PMIX_*, OPAL_*, PRTE_*, ORTE_*). A child process started from a
/// process that runs MPI (e.g. `mpirun`, or another `stiffsoft`) must not inherit them.
bool is_mpi_launcher_variable(std::string_view entry);

/// The names of this process's environment variables for which is_mpi_launcher_variable() holds.
std::vector<std::string> mpi_launcher_variables();

}  // namespace stiffsoft
