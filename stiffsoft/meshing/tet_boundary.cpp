#include <stiffsoft/meshing/tet_boundary.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace stiffsoft {
namespace {

/// outward local faces of a positively oriented tetrahedron
constexpr int outward_face[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};

struct FaceUse {
  std::array<int, 3> sorted;  // node indices, ascending: the key shared by both tets of an inner face
  int tet;
  int local;
  bool operator<(const FaceUse& o) const {
    if (sorted != o.sorted) return sorted < o.sorted;
    return tet != o.tet ? tet < o.tet : local < o.local;
  }
};

}  // namespace

TetBoundary boundary_surface(const TetMesh& mesh, const std::string& what) {
  const auto& T = mesh.T;
  std::vector<FaceUse> uses;
  uses.reserve(4 * static_cast<size_t>(T.rows()));
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int f = 0; f < 4; ++f) {
      std::array<int, 3> key{T(t, outward_face[f][0]), T(t, outward_face[f][1]), T(t, outward_face[f][2])};
      std::sort(key.begin(), key.end());
      uses.push_back({key, static_cast<int>(t), f});
    }
  std::sort(uses.begin(), uses.end());

  std::vector<std::pair<int, int>> boundary;  // (tet, local face)
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].sorted == uses[i].sorted) ++j;
    if (j - i > 2)
      throw std::runtime_error(what + ": triangle (" + std::to_string(uses[i].sorted[0]) + ", " +
                               std::to_string(uses[i].sorted[1]) + ", " + std::to_string(uses[i].sorted[2]) +
                               ") belongs to " + std::to_string(j - i) +
                               " tetrahedra (not a manifold tet mesh)");
    if (j - i == 1) boundary.emplace_back(uses[i].tet, uses[i].local);
    i = j;
  }
  std::sort(boundary.begin(), boundary.end());

  std::vector<int> vertex_of_node(static_cast<size_t>(mesh.X.rows()), -1);
  for (const auto& [t, f] : boundary)
    for (int k = 0; k < 3; ++k) vertex_of_node[static_cast<size_t>(T(t, outward_face[f][k]))] = 0;
  TetBoundary b;
  int count = 0;
  for (auto& v : vertex_of_node)
    if (v == 0) v = count++;
  b.node_of_vertex.resize(count);
  b.surface.V.resize(count, 3);
  for (size_t i = 0; i < vertex_of_node.size(); ++i)
    if (vertex_of_node[i] >= 0) {
      b.node_of_vertex[vertex_of_node[i]] = static_cast<int>(i);
      b.surface.V.row(vertex_of_node[i]) = mesh.X.row(static_cast<Eigen::Index>(i));
    }
  b.surface.F.resize(static_cast<Eigen::Index>(boundary.size()), 3);
  b.tet_of_face.resize(static_cast<Eigen::Index>(boundary.size()));
  for (size_t i = 0; i < boundary.size(); ++i) {
    const auto [t, f] = boundary[i];
    for (int k = 0; k < 3; ++k)
      b.surface.F(static_cast<Eigen::Index>(i), k) =
          vertex_of_node[static_cast<size_t>(T(t, outward_face[f][k]))];
    b.tet_of_face[static_cast<Eigen::Index>(i)] = t;
  }
  b.E = edges(b.surface.F);
  return b;
}

}  // namespace stiffsoft
