#pragma once
/// @file A structured tetrahedral mesh of an axis-aligned box, for tests and convergence studies.

#include <Eigen/Core>

namespace stiffsoft::fem {

/// A tetrahedral mesh.
struct TetMesh {
  Eigen::MatrixX3d X;  ///< node positions, |N|×3 (m)
  Eigen::MatrixX4i T;  ///< tetrahedra, |T|×4 zero-based, positively oriented (det D_m > 0)
};

/// The box [0, size.x] × [0, size.y] × [0, size.z] (m) cut into cells.x × cells.y × cells.z hexahedra,
/// each split into 6 tetrahedra around its main diagonal (Kuhn / Freudenthal split; the same split
/// in every cell makes the mesh conforming). Node (i, j, k) has index i + (nx+1)(j + (ny+1) k).
/// Throws std::invalid_argument unless every size > 0 and every cell count ≥ 1.
TetMesh box_tet_mesh(const Eigen::Vector3d& size, const Eigen::Vector3i& cells);

}  // namespace stiffsoft::fem
