/// @file Splitting a command line between PETSc's options and the program's own (apps/cli).

#include <gtest/gtest.h>

#include <iterator>
#include <string>
#include <vector>

#include "apps/cli/petsc_arguments.hpp"

using namespace stiffsoft;

TEST(SplitPetscArguments, PetscOptionsGoToPetscAndTheRestToTheProgram) {
  const char* argv[] = {"stiffsoft",    "run",           "scene.json", "-ksp_type",   "cg",        "-o",
                        "out",          "-log_view",     "--steps",    "3",           "-ksp_rtol", "-1e-3",
                        "-ksp_monitor", "-pc_type",      "gamg",       "-help_petsc", "--threads", "2",
                        "-ksp_view",    "ascii:view.txt"};
  const SplitCommandLine split = split_petsc_arguments(int(std::size(argv)), argv);
  EXPECT_EQ(split.program, (std::vector<std::string>{"stiffsoft", "run", "scene.json", "-o", "out", "--steps",
                                                     "3", "--threads", "2"}));
  EXPECT_EQ(split.petsc, (std::vector<std::string>{"stiffsoft", "-ksp_type", "cg", "-log_view", "-ksp_rtol",
                                                   "-1e-3", "-ksp_monitor", "-pc_type", "gamg", "-help",
                                                   "-ksp_view", "ascii:view.txt"}));
  const char* flag_first[] = {"stiffsoft", "-log_view", "run", "scene.json"};
  EXPECT_EQ(split_petsc_arguments(4, flag_first).program,
            (std::vector<std::string>{"stiffsoft", "run", "scene.json"}));
  EXPECT_FALSE(is_petsc_option("--ksp_type"));
  EXPECT_FALSE(is_petsc_option("-o"));
  EXPECT_TRUE(is_petsc_option("-pc_gamg_threshold"));
}
