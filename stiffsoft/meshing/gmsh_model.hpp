#pragma once
/// @file Moving tetrahedral meshes between stiffsoft and the current gmsh model.

#include <string>

#include <stiffsoft/meshing/tet_mesh.hpp>

namespace stiffsoft {

/// The linear tetrahedra of the current gmsh model (all volume entities) as a TetMesh. Call only
/// inside run_gmsh(). Nodes are the ones the tetrahedra use, numbered by ascending gmsh node tag;
/// tetrahedra with negative volume are reoriented (nodes 1 and 2 swapped). Every physical group
/// (points, curves, surfaces or volumes) becomes a node set of the nodes of its elements that the
/// tetrahedra use, named by the group's name, or "physical_<dim>_<tag>" when it has none; groups
/// of the same name are merged.
/// @throws std::runtime_error naming `what` when there are no tetrahedra, when a volume holds
/// elements other than linear tetrahedra (e.g. second-order tetrahedra, hexahedra), or when the
/// mesh fails check_tet_mesh()
TetMesh tet_mesh_from_gmsh_model(const std::string& what);

/// Replaces the current gmsh model by `mesh`: one discrete volume holding all nodes and the
/// tetrahedra (gmsh node tag = index + 1, tet element tag = index + 1); each non-empty node set
/// becomes a discrete point entity holding one point element (type 15) per member, in a physical
/// group of dimension 0 named after the set (empty sets are dropped). Call only inside run_gmsh().
void tet_mesh_to_gmsh_model(const TetMesh& mesh);

}  // namespace stiffsoft
