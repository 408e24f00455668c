#pragma once
/// @file Closed triangle surfaces: the geometry of an affine body and of every contact surface.

#include <Eigen/Core>

namespace stiffsoft {

/// A triangle surface mesh.
struct SurfaceMesh {
  /// vertex positions, |V|×3, metres
  Eigen::MatrixX3d V;
  /// triangles, |F|×3 indices into V, counter-clockwise seen from outside (outward normals)
  Eigen::MatrixX3i F;
};

/// The unique undirected edges of a triangle mesh, |E|×2, each with the smaller index first,
/// sorted lexicographically.
Eigen::MatrixX2i edges(const Eigen::MatrixX3i& F);

}  // namespace stiffsoft
