#include <stiffsoft/meshing/gmsh_model.hpp>

#include <gmsh.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace stiffsoft {
namespace {

constexpr int gmsh_point = 15;  // 1-node point element
constexpr int gmsh_tet4 = 4;    // 4-node tetrahedron

}  // namespace

TetMesh tet_mesh_from_gmsh_model(const std::string& what) {
  std::vector<int> volume_types;
  gmsh::model::mesh::getElementTypes(volume_types, 3);
  for (int type : volume_types)
    if (type != gmsh_tet4) {
      std::string name;
      int dim = 0, order = 0, num_nodes = 0, num_primary = 0;
      std::vector<double> local;
      gmsh::model::mesh::getElementProperties(type, name, dim, order, num_nodes, local, num_primary);
      throw std::runtime_error(what + ": has volume elements of gmsh type " + std::to_string(type) + " (" +
                               name + "); only linear 4-node tetrahedra are supported");
    }

  std::vector<std::size_t> tet_tags, tet_nodes;
  gmsh::model::mesh::getElementsByType(gmsh_tet4, tet_tags, tet_nodes);
  if (tet_tags.empty())
    throw std::runtime_error(
        what +
        ": contains no tetrahedra (a .msh saved with physical groups holds only the "
        "elements of those groups: add a physical volume or save with Mesh.SaveAll = 1)");

  std::vector<std::size_t> node_tags;
  std::vector<double> coordinates, parametric;
  gmsh::model::mesh::getNodes(node_tags, coordinates, parametric, -1, -1, false, false);
  std::unordered_map<std::size_t, std::size_t> position_of_tag;  // gmsh tag → position in node_tags
  position_of_tag.reserve(node_tags.size());
  for (std::size_t i = 0; i < node_tags.size(); ++i) position_of_tag.emplace(node_tags[i], i);

  // Nodes the tetrahedra use, by ascending tag: the numbering does not depend on gmsh's entity order.
  std::vector<std::size_t> used(tet_nodes);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::unordered_map<std::size_t, int> index_of_tag;
  index_of_tag.reserve(used.size());
  TetMesh mesh;
  mesh.X.resize(static_cast<Eigen::Index>(used.size()), 3);
  for (std::size_t i = 0; i < used.size(); ++i) {
    const auto found = position_of_tag.find(used[i]);
    if (found == position_of_tag.end())
      throw std::runtime_error(what + ": a tetrahedron uses node " + std::to_string(used[i]) +
                               ", which does not exist");
    index_of_tag.emplace(used[i], static_cast<int>(i));
    for (int d = 0; d < 3; ++d) mesh.X(static_cast<Eigen::Index>(i), d) = coordinates[3 * found->second + d];
  }
  mesh.T.resize(static_cast<Eigen::Index>(tet_tags.size()), 4);
  for (std::size_t t = 0; t < tet_tags.size(); ++t)
    for (int k = 0; k < 4; ++k)
      mesh.T(static_cast<Eigen::Index>(t), k) = index_of_tag.at(tet_nodes[4 * t + k]);

  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  for (const auto& [dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    if (name.empty()) name = "physical_" + std::to_string(dim) + "_" + std::to_string(tag);
    std::vector<std::size_t> group_nodes;
    std::vector<double> group_coordinates;
    gmsh::model::mesh::getNodesForPhysicalGroup(dim, tag, group_nodes, group_coordinates);
    auto& set = mesh.node_sets[name];
    for (std::size_t n : group_nodes)
      if (const auto found = index_of_tag.find(n); found != index_of_tag.end()) set.push_back(found->second);
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }

  orient_tets_positively(mesh);
  check_tet_mesh(mesh, what);
  return mesh;
}

void tet_mesh_to_gmsh_model(const TetMesh& mesh) {
  gmsh::clear();
  gmsh::model::add("stiffsoft");
  const int volume = gmsh::model::addDiscreteEntity(3);
  std::vector<std::size_t> node_tags(static_cast<std::size_t>(mesh.X.rows()));
  std::vector<double> coordinates;
  coordinates.reserve(3 * node_tags.size());
  for (Eigen::Index i = 0; i < mesh.X.rows(); ++i) {
    node_tags[static_cast<std::size_t>(i)] = static_cast<std::size_t>(i) + 1;
    for (int d = 0; d < 3; ++d) coordinates.push_back(mesh.X(i, d));
  }
  gmsh::model::mesh::addNodes(3, volume, node_tags, coordinates);

  std::vector<std::size_t> tet_tags(static_cast<std::size_t>(mesh.T.rows())), tet_nodes;
  tet_nodes.reserve(4 * tet_tags.size());
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    tet_tags[static_cast<std::size_t>(t)] = static_cast<std::size_t>(t) + 1;
    for (int k = 0; k < 4; ++k) tet_nodes.push_back(static_cast<std::size_t>(mesh.T(t, k)) + 1);
  }
  gmsh::model::mesh::addElementsByType(volume, gmsh_tet4, tet_tags, tet_nodes);

  // One point entity per set, holding a point element per member; the nodes stay on the volume.
  // (An entity per node would be exact gmsh style too, but writing thousands of entities takes seconds.)
  std::size_t element_tag = tet_tags.size();
  for (const auto& [name, nodes] : mesh.node_sets) {
    if (nodes.empty()) continue;
    const int point = gmsh::model::addDiscreteEntity(0);
    std::vector<std::size_t> point_tags, point_nodes;
    for (int i : nodes) {
      point_tags.push_back(++element_tag);
      point_nodes.push_back(static_cast<std::size_t>(i) + 1);
    }
    gmsh::model::mesh::addElementsByType(point, gmsh_point, point_tags, point_nodes);
    const int group = gmsh::model::addPhysicalGroup(0, {point});
    gmsh::model::setPhysicalName(0, group, name);
  }
}

}  // namespace stiffsoft
