#include "apps/cli/petsc_command_line.hpp"

namespace stiffsoft {

namespace {

std::vector<std::string> petsc_options(const SplitCommandLine& split) {
  return {split.petsc.begin() + 1, split.petsc.end()};
}

}  // namespace

PetscCommandLine::PetscCommandLine(int argc, const char* const* argv)
    : m_split(split_petsc_arguments(argc, argv)),
      m_program_pointers(argv_pointers(m_split.program)),
      m_session(petsc_options(m_split), m_split.petsc.front()) {}

}  // namespace stiffsoft
