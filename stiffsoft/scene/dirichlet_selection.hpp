#pragma once
/// @file Which nodes of a soft body a Dirichlet condition selects, and how they then move.

#include <Eigen/Core>
#include <string>
#include <vector>

#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/scene/scene.hpp>
#include <stiffsoft/meshing/tet_mesh.hpp>

namespace stiffsoft {

/// The nodes of `mesh` (world positions) that `condition` selects, ascending. A node set is
/// looked up by name in mesh.node_sets.
std::vector<int> dirichlet_nodes(const TetMesh& mesh, const DirichletDescription& condition);

/// Per-node motion and velocity of a soft body from its Dirichlet conditions (later conditions
/// override earlier ones): Fixed for zero velocity, Kinematic otherwise, Dynamic for the rest.
/// A condition that selects no node is a SceneError naming `file` and `path`.dirichlet[j].
void apply_dirichlet(const TetMesh& mesh, const std::vector<DirichletDescription>& conditions,
                     const std::string& body_name, const std::string& file, const std::string& path,
                     std::vector<Motion>& motion, Eigen::MatrixX3d& velocity);

}  // namespace stiffsoft
