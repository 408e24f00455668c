#include "apps/cli/petsc_command_line.hpp"

namespace stiffsoft {

namespace {

std::vector<std::string> petsc_options(const SplitCommandLine& split) {
  return {split.petsc.begin() + 1, split.petsc.end()};
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> p;
  for (std::string& s : strings) p.push_back(s.data());
  p.push_back(nullptr);
  return p;
}

}  // namespace

PetscCommandLine::PetscCommandLine(int argc, const char* const* argv)
    : m_split(split_petsc_arguments(argc, argv)),
      m_program_pointers(pointers(m_split.program)),
      m_session(petsc_options(m_split), m_split.petsc.front()) {}

}  // namespace stiffsoft
