#pragma once
/// @file Linear tetrahedral meshes of soft bodies, and their always-on validity checks.

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace stiffsoft {

/// A linear (4-node) tetrahedral mesh. Indices are zero-based.
struct TetMesh {
  /// node positions, |X|×3, metres
  Eigen::MatrixX3d X;
  /// tetrahedra, |T|×4 indices into X, positively oriented: det[x1−x0, x2−x0, x3−x0] > 0
  Eigen::MatrixX4i T;
  /// named node sets (e.g. from gmsh physical groups), each sorted ascending without repeats
  std::map<std::string, std::vector<int>> node_sets;
};

/// Relative volume at or below which a tetrahedron counts as degenerate: |V| ≤ 1e-12 · ℓ̄³,
/// ℓ̄ the mean of its six edge lengths (a sliver this flat has no usable deformation gradient).
inline constexpr double degenerate_tet_volume_tolerance = 1e-12;

/// Signed volume of tetrahedron t, V = det[x1−x0, x2−x0, x3−x0] / 6 (m³); positive when
/// positively oriented. Indices must be in range.
double tet_signed_volume(const TetMesh& mesh, Eigen::Index t);

/// Signed volumes of all tetrahedra, |T|, m³.
Eigen::VectorXd tet_signed_volumes(const TetMesh& mesh);

/// The first reason `mesh` is not a valid simulation mesh, or nothing. Checked in this order:
/// at least one tetrahedron; finite coordinates; indices in range; no tetrahedron repeating a node;
/// every node used by some tetrahedron (no unreferenced nodes); node-set indices in range, sorted
/// and unique; no degenerate tetrahedron (|V| ≤ degenerate_tet_volume_tolerance · ℓ̄³); no inverted
/// tetrahedron (V < 0). The message names the node, tetrahedron or set (0-based indices).
std::optional<std::string> tet_mesh_problem(const TetMesh& mesh);

/// Throws std::runtime_error("<what>: <problem>") when tet_mesh_problem() finds one.
/// @param what the body or file the mesh comes from, for the message
void check_tet_mesh(const TetMesh& mesh, const std::string& what);

/// Swaps nodes 1 and 2 of every tetrahedron with negative signed volume (making it positive);
/// degenerate ones are left for check_tet_mesh() to report. Returns how many were swapped.
int orient_tets_positively(TetMesh& mesh);

/// Removes the nodes that no tetrahedron uses, keeping the others in order, renumbering T and the
/// node sets (members that are removed leave their sets; a set may become empty). Returns how many
/// nodes were removed. Indices of T must be in range.
int remove_unreferenced_nodes(TetMesh& mesh);

/// Total volume Σ V_t of the tetrahedra (m³).
double tet_mesh_volume(const TetMesh& mesh);

}  // namespace stiffsoft
