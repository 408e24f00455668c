#include <stiffsoft/meshing/tet_mesh.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace stiffsoft {
namespace {

std::string tet_text(const TetMesh& mesh, Eigen::Index t) {
  std::ostringstream s;
  s << "tetrahedron " << t << " (" << mesh.T(t, 0) << ", " << mesh.T(t, 1) << ", " << mesh.T(t, 2) << ", "
    << mesh.T(t, 3) << ")";
  return s.str();
}

double mean_edge_length(const TetMesh& mesh, Eigen::Index t) {
  double sum = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) sum += (mesh.X.row(mesh.T(t, b)) - mesh.X.row(mesh.T(t, a))).norm();
  return sum / 6.0;
}

}  // namespace

double tet_signed_volume(const TetMesh& mesh, Eigen::Index t) {
  const Eigen::Vector3d x0 = mesh.X.row(mesh.T(t, 0));
  const Eigen::Vector3d e1 = mesh.X.row(mesh.T(t, 1)).transpose() - x0;
  const Eigen::Vector3d e2 = mesh.X.row(mesh.T(t, 2)).transpose() - x0;
  const Eigen::Vector3d e3 = mesh.X.row(mesh.T(t, 3)).transpose() - x0;
  return e1.cross(e2).dot(e3) / 6.0;
}

Eigen::VectorXd tet_signed_volumes(const TetMesh& mesh) {
  Eigen::VectorXd V(mesh.T.rows());
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) V[t] = tet_signed_volume(mesh, t);
  return V;
}

double tet_mesh_volume(const TetMesh& mesh) { return tet_signed_volumes(mesh).sum(); }

std::optional<std::string> tet_mesh_problem(const TetMesh& mesh) {
  const auto& X = mesh.X;
  const auto& T = mesh.T;
  if (T.rows() == 0) return "has no tetrahedra";
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    if (!X.row(i).allFinite()) return "node " + std::to_string(i) + " has a non-finite coordinate";

  std::vector<char> used(static_cast<size_t>(X.rows()), 0);
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    for (int k = 0; k < 4; ++k) {
      if (T(t, k) < 0 || T(t, k) >= X.rows())
        return tet_text(mesh, t) + " has node index " + std::to_string(T(t, k)) + " out of range [0, " +
               std::to_string(X.rows()) + ")";
      used[static_cast<size_t>(T(t, k))] = 1;
    }
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        if (T(t, a) == T(t, b)) return tet_text(mesh, t) + " repeats a node (degenerate)";
  }
  for (size_t i = 0; i < used.size(); ++i)
    if (!used[i]) return "node " + std::to_string(i) + " is used by no tetrahedron (unreferenced node)";

  for (const auto& [name, nodes] : mesh.node_sets)
    for (size_t k = 0; k < nodes.size(); ++k) {
      if (nodes[k] < 0 || nodes[k] >= X.rows())
        return "node set '" + name + "' has node index " + std::to_string(nodes[k]) + " out of range [0, " +
               std::to_string(X.rows()) + ")";
      if (k > 0 && nodes[k] <= nodes[k - 1]) return "node set '" + name + "' is not sorted and unique";
    }

  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    const double V = tet_signed_volume(mesh, t);
    const double l = mean_edge_length(mesh, t);
    // `!(…)` also catches NaN.
    if (!(std::abs(V) > degenerate_tet_volume_tolerance * l * l * l))
      return tet_text(mesh, t) + " has (numerically) zero volume " + std::to_string(V) + " m³ (degenerate)";
    if (V < 0.0) return tet_text(mesh, t) + " is inverted (volume " + std::to_string(V) + " m³ < 0)";
  }
  return std::nullopt;
}

void check_tet_mesh(const TetMesh& mesh, const std::string& what) {
  if (const auto problem = tet_mesh_problem(mesh)) throw std::runtime_error(what + ": " + *problem);
}

int orient_tets_positively(TetMesh& mesh) {
  int swapped = 0;
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t)
    if (tet_signed_volume(mesh, t) < 0.0) {
      std::swap(mesh.T(t, 1), mesh.T(t, 2));
      ++swapped;
    }
  return swapped;
}

int remove_unreferenced_nodes(TetMesh& mesh) {
  const Eigen::Index n = mesh.X.rows();
  std::vector<int> new_index(static_cast<size_t>(n), -1);
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t)
    for (int k = 0; k < 4; ++k) new_index[static_cast<size_t>(mesh.T(t, k))] = 0;
  int kept = 0;
  for (auto& i : new_index)
    if (i == 0) i = kept++;
  if (kept == n) return 0;

  Eigen::MatrixX3d X(kept, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    if (new_index[static_cast<size_t>(i)] >= 0) X.row(new_index[static_cast<size_t>(i)]) = mesh.X.row(i);
  mesh.X = std::move(X);
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t)
    for (int k = 0; k < 4; ++k) mesh.T(t, k) = new_index[static_cast<size_t>(mesh.T(t, k))];
  for (auto& [name, nodes] : mesh.node_sets) {
    std::vector<int> kept_nodes;
    for (int i : nodes)
      if (i >= 0 && i < n && new_index[static_cast<size_t>(i)] >= 0)
        kept_nodes.push_back(new_index[static_cast<size_t>(i)]);
    nodes = std::move(kept_nodes);
  }
  return static_cast<int>(n) - kept;
}

}  // namespace stiffsoft
