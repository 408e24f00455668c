#include "apps/cli/petsc_command_line.hpp"

#include <cstdlib>

namespace stiffsoft {

namespace {

std::vector<std::string> petsc_options(const SplitCommandLine& split) {
  return {split.petsc.begin() + 1, split.petsc.end()};
}

/// Whether an MPI launcher started this process: OpenMPI's mpirun, or a PMI/PMIx one (MPICH's
/// Hydra, Slurm's srun).
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMI_RANK", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

}  // namespace

PetscCommandLine::PetscCommandLine(int argc, const char* const* argv)
    : m_split(split_petsc_arguments(argc, argv)),
      m_program_pointers(argv_pointers(m_split.program)) {
  if (m_split.petsc.size() > 1 || launched_by_mpi()) m_session.emplace(petsc_options(m_split), m_split.petsc.front());
}

}  // namespace stiffsoft
