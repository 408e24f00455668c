#pragma once
/// @file Volume, first and second moments of the solid enclosed by a closed triangle surface.

#include <Eigen/Core>

#include <stiffsoft/meshing/surface_mesh.hpp>

namespace stiffsoft {

/// Geometric moments of the solid Ω enclosed by a closed, outward-oriented surface (unit density).
struct MassMoments {
  /// V = \int_\Omega dV, m³ (negative when the surface is oriented inward)
  double volume = 0.0;
  /// \int_\Omega x \, dV, 3-vector, m⁴ (the centroid is first / volume)
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  /// \int_\Omega x x^T dV, symmetric 3×3, m⁵ (the inertia tensor about the origin is tr(S) I − S)
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
};

/// Exact moments of a closed triangle mesh by the divergence theorem: the solid is the signed sum of
/// the tetrahedra (0, a, b, c) over the faces (a, b, c). For one tetrahedron with V = a·(b×c)/6:
/// \int x dV = V (a + b + c) / 4 and \int x x^T dV = V/20 (a a^T + b b^T + c c^T + s s^T), s = a + b + c
/// (Tonon 2004, "Explicit exact formulas for the 3-D tetrahedron inertia tensor").
/// Exact up to floating-point rounding for any closed mesh; meaningless for an open one.
MassMoments mass_moments(const SurfaceMesh& mesh);

}  // namespace stiffsoft
