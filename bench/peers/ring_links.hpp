#pragma once
/// @file Whether two closed chain links are still linked: the linking number of their centre lines.

#include <Eigen/Core>

namespace stiffsoft::peers {

/// Linking number of the closed polygons A and B (rows are vertices, world frame, m), for a
/// PLANAR CONVEX A (a rigid or affine image of a torus centre line): the signed number of times
/// B's segments cross the flat polygonal disc bounded by A. Two interlocked chain links give ±1,
/// separate ones 0. A link that slipped through another (tunnelled) changes it.
int linking_number(const Eigen::MatrixX3d& A, const Eigen::MatrixX3d& B);

}  // namespace stiffsoft::peers
