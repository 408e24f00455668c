# Every dependency is a Debian package (scripts/setup.sh installs them); nothing is downloaded.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(TBB REQUIRED)
find_package(nlohmann_json REQUIRED)
find_package(CLI11 REQUIRED)
find_package(spdlog REQUIRED)
find_package(CGAL REQUIRED)
# The library reads and writes XML files only; rendering (RenderingCore onwards) is for the
# `stiffsoft render` command alone (apps/render/).
find_package(VTK REQUIRED COMPONENTS IOXML CommonCore CommonDataModel
  RenderingCore RenderingOpenGL2 RenderingFreeType RenderingAnnotation InteractionStyle
  FiltersGeometry FiltersSources FiltersCore ImagingCore IOImage)
find_package(MPI REQUIRED COMPONENTS C CXX)
# zlib compresses the frames (stiffsoft/io/vtu_text.hpp), as VTK would.
find_package(ZLIB REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(PETSC REQUIRED IMPORTED_TARGET PETSc)

# SuiteSparse 5.12 ships neither a CMake config nor a pkg-config file.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIB cholmod REQUIRED)
add_library(stiffsoft_cholmod INTERFACE)
target_include_directories(stiffsoft_cholmod SYSTEM INTERFACE ${CHOLMOD_INCLUDE_DIR})
target_link_libraries(stiffsoft_cholmod INTERFACE ${CHOLMOD_LIB})
# CHOLMOD runs its supernodal loops on OpenMP (libgomp); the solver sets their threads
# (cholmod_solver.cpp). Only the runtime is linked: no -fopenmp, so Eigen stays serial.
find_package(OpenMP REQUIRED COMPONENTS CXX)
target_link_libraries(stiffsoft_cholmod INTERFACE ${OpenMP_CXX_LIBRARIES})

# gmsh 4.8 ships no CMake config.
find_path(GMSH_INCLUDE_DIR gmsh.h REQUIRED)
find_library(GMSH_LIB gmsh REQUIRED)
add_library(stiffsoft_gmsh INTERFACE)
target_include_directories(stiffsoft_gmsh SYSTEM INTERFACE ${GMSH_INCLUDE_DIR})
target_link_libraries(stiffsoft_gmsh INTERFACE ${GMSH_LIB})

if(STIFFSOFT_TESTS)
  find_package(GTest REQUIRED)
endif()
