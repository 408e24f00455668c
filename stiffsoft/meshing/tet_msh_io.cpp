#include <stiffsoft/meshing/tet_msh_io.hpp>

#include <gmsh.h>
#include <unistd.h>

#include <atomic>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include <stiffsoft/meshing/gmsh_model.hpp>
#include <stiffsoft/meshing/gmsh_session.hpp>
#include <stiffsoft/meshing/isolated_call.hpp>
#include <stiffsoft/meshing/tet_mesh_binary.hpp>

namespace stiffsoft {

TetMesh read_msh(const std::filesystem::path& file, bool verbose) {
  const std::string what = file.string();
  {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::runtime_error(what + ": cannot open file");
    // gmsh::open runs anything that is not a mesh as a .geo script: make sure it is a mesh file.
    std::string line;
    while (std::getline(in, line) && line.find_first_not_of(" \t\r") == std::string::npos) {
    }
    if (line.find_first_not_of(" \t\r") == std::string::npos || line.rfind("$MeshFormat", 0) != 0)
      throw std::runtime_error(what + ": not a gmsh .msh file (expected '$MeshFormat' on the first line)");
  }
  // gmsh 4.8 crashes on some malformed files (found by fuzzing): read in a child process, which
  // hands the mesh back in the mesh cache's binary format.
  static std::atomic<unsigned long> counter{0};
  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() /
      ("stiffsoft-read-msh-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1)) + ".tetmesh");
  std::error_code ignored;
  try {
    run_isolated(what, "gmsh's .msh reader", [&] {
      TetMesh mesh;
      run_gmsh(what, verbose, [&] {
        gmsh::open(file.string());
        // gmsh reports some syntax errors in the log without throwing.
        if (const std::string errors = gmsh_logged_errors(); !errors.empty())
          throw std::runtime_error(what + ": gmsh: " + errors);
        mesh = tet_mesh_from_gmsh_model(what);
      });
      write_tet_mesh_binary(scratch, mesh);
    });
    TetMesh mesh = read_tet_mesh_binary(scratch);
    std::filesystem::remove(scratch, ignored);
    return mesh;
  } catch (...) {
    std::filesystem::remove(scratch, ignored);
    throw;
  }
}

void write_msh(const std::filesystem::path& file, const TetMesh& mesh, bool verbose) {
  const std::string what = file.string();
  check_tet_mesh(mesh, what);
  static std::atomic<unsigned long> counter{0};
  // Same folder, so that the rename is one atomic directory update; ends in .msh, which is how gmsh
  // picks the format.
  std::string name = ".";
  name += file.filename().string();
  name += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1)) + ".msh";
  const std::filesystem::path tmp = file.parent_path() / name;
  std::error_code ignored;
  try {
    run_gmsh(what, verbose, [&] {
      tet_mesh_to_gmsh_model(mesh);
      gmsh::option::setNumber("Mesh.SaveAll", 1);
      gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
      gmsh::option::setNumber("Mesh.Binary", 0);
      gmsh::write(tmp.string());
      if (const std::string errors = gmsh_logged_errors(); !errors.empty())
        throw std::runtime_error(what + ": gmsh: " + errors);
    });
  } catch (...) {
    std::filesystem::remove(tmp, ignored);
    throw;
  }
  if (!std::filesystem::is_regular_file(tmp))
    throw std::runtime_error(what + ": cannot write file (gmsh wrote no temporary file '" + tmp.string() +
                             "')");
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error(what + ": cannot write file: rename from '" + tmp.string() +
                             "' failed: " + ec.message());
  }
}

}  // namespace stiffsoft
