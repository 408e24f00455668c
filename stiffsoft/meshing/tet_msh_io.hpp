#pragma once
/// @file Reading and writing tetrahedral meshes as gmsh .msh files.

#include <filesystem>

#include <stiffsoft/meshing/tet_mesh.hpp>

namespace stiffsoft {

/// Reads the linear tetrahedra of a gmsh .msh file (any version gmsh 4.8 reads: 2.2, 4.1, ASCII
/// or binary). Nodes no tetrahedron uses are dropped, the rest numbered by ascending gmsh tag;
/// negatively oriented tetrahedra are reoriented; every physical group (points, curves, surfaces,
/// volumes) becomes a node set by its name ("physical_<dim>_<tag>" when unnamed), holding the
/// group's nodes that the tetrahedra use. Other elements (triangles, lines, points) are ignored.
/// gmsh reads the file in a child process (run_isolated()), so that a file that crashes gmsh's
/// reader is an error like any other malformed file.
/// @param verbose print gmsh's messages
/// @throws std::runtime_error naming the file when it cannot be opened, does not start with
/// `$MeshFormat`, gmsh fails to read it, it holds no tetrahedra or non-tetrahedral volume elements,
/// or the mesh fails check_tet_mesh(), and when gmsh crashes reading it
TetMesh read_msh(const std::filesystem::path& file, bool verbose = false);

/// Writes `mesh` as an ASCII MSH 4.1 file that read_msh() reads back to the same mesh (positions
/// to 16 significant digits): one volume of tetrahedra, and each non-empty node set as a physical
/// point group of that name. Written atomically (a temporary file in the same folder, renamed).
/// @throws std::runtime_error naming the file when it cannot be written
void write_msh(const std::filesystem::path& file, const TetMesh& mesh, bool verbose = false);

}  // namespace stiffsoft
