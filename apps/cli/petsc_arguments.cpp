#include "apps/cli/petsc_arguments.hpp"

#include <unistd.h>

#include <array>
#include <cstdlib>

namespace stiffsoft {

namespace {

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

bool is_number(std::string_view s) {
  if (s.empty()) return false;
  const std::string text(s);
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

/// PETSc options whose value is optional (flags, viewers).
bool has_optional_value(std::string_view option) {
  constexpr std::array<std::string_view, 4> parts{"monitor", "view", "converged_reason", "options_left"};
  for (std::string_view part : parts)
    if (option.find(part) != std::string_view::npos) return true;
  return option == "-info" || starts_with(option, "-malloc") || option == "-help_petsc" ||
         option == "-on_error_abort" || option == "-no_signal_handler" || option == "-fp_trap" ||
         option == "-memory_view";
}

/// A value a flag-like PETSc option accepts: a boolean or a viewer specification.
bool looks_like_flag_value(std::string_view value) {
  constexpr std::array<std::string_view, 12> words{"true",  "false", "yes",    "no",     "0",      "1",
                                                   "ascii", "draw",  "binary", "stdout", "stderr", "hdf5"};
  for (std::string_view w : words)
    if (value == w) return true;
  return value.find(':') != std::string_view::npos;
}

}  // namespace

bool is_petsc_option(std::string_view a) {
  constexpr std::array<std::string_view, 9> prefixes{"-ksp_",     "-pc_",    "-mat_", "-vec_", "-log_",
                                                     "-options_", "-malloc", "-sub_", "-info"};
  if (a.size() < 2 || a[0] != '-' || a[1] == '-') return false;
  for (std::string_view p : prefixes)
    if (starts_with(a, p)) return true;
  return a == "-help_petsc" || a == "-on_error_abort" || a == "-no_signal_handler" || a == "-fp_trap" ||
         a == "-memory_view";
}

SplitCommandLine split_petsc_arguments(int argc, const char* const* argv) {
  SplitCommandLine split;
  const std::string program = argc > 0 ? argv[0] : "stiffsoft";
  split.petsc.push_back(program);
  split.program.push_back(program);
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (!is_petsc_option(a)) {
      split.program.emplace_back(a);
      continue;
    }
    split.petsc.emplace_back(a == "-help_petsc" ? std::string_view("-help") : a);
    if (i + 1 >= argc) continue;
    const std::string_view next = argv[i + 1];
    const bool value_shaped = !starts_with(next, "-") || is_number(next);
    if (value_shaped && (!has_optional_value(a) || looks_like_flag_value(next)))
      split.petsc.emplace_back(argv[++i]);
  }
  return split;
}

bool is_mpi_launcher_variable(std::string_view entry) {
  for (const std::string_view prefix : {"OMPI_", "PMIX_", "OPAL_", "PRTE_", "ORTE_"})
    if (starts_with(entry, prefix)) return true;
  return false;
}

std::vector<std::string> mpi_launcher_variables() {
  std::vector<std::string> names;
  for (char** e = environ; *e; ++e) {
    const std::string_view entry(*e);
    if (is_mpi_launcher_variable(entry)) names.emplace_back(entry.substr(0, entry.find('=')));
  }
  return names;
}

}  // namespace stiffsoft
