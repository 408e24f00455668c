#pragma once
/// @file The boundary surface of a tetrahedral mesh: the contact surface of a soft body.

#include <Eigen/Core>
#include <string>

#include <stiffsoft/meshing/surface_mesh.hpp>
#include <stiffsoft/meshing/tet_mesh.hpp>

namespace stiffsoft {

/// The boundary of a tet mesh as a triangle surface over its own vertex numbering.
struct TetBoundary {
  /// the boundary triangles: V = X.rows(node_of_vertex), |V_s|×3 (m); F indexes V, outward
  /// (counter-clockwise seen from outside, normal pointing away from the face's tetrahedron)
  SurfaceMesh surface;
  /// tet node of each surface vertex, |V_s|, strictly increasing (surface vertex i is node
  /// node_of_vertex[i])
  Eigen::VectorXi node_of_vertex;
  /// unique undirected surface edges, |E|×2, indices into surface.V (edges(surface.F))
  Eigen::MatrixX2i E;
  /// tetrahedron each boundary triangle belongs to, |F|
  Eigen::VectorXi tet_of_face;
};

/// The triangles that belong to exactly one tetrahedron, oriented outward, in order of (tetrahedron,
/// local face). For a positively oriented tet (x0, x1, x2, x3) the outward faces are (0, 2, 1),
/// (0, 1, 3), (1, 2, 3), (0, 3, 2). Requires a mesh that passes check_tet_mesh (positive volumes).
/// @throws std::runtime_error naming `what` when a triangle is shared by more than two tetrahedra
/// (not a 3-manifold)
TetBoundary boundary_surface(const TetMesh& mesh, const std::string& what = "tet mesh");

}  // namespace stiffsoft
