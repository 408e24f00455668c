#pragma once
/// @file Closed triangle meshes of primitive shapes, centred at the origin.

#include <Eigen/Core>

#include <stiffsoft/meshing/surface_mesh.hpp>

namespace stiffsoft {

/// A primitive shape, centred at the origin, axis of symmetry along y.
struct PrimitiveShape {
  /// which shape
  enum class Type { Box, Sphere, Cylinder, Torus, Plane } type = Type::Box;
  /// box: edge lengths along x, y, z (m); plane: size along x, thickness along y, size along z (m)
  Eigen::Vector3d extents{1.0, 1.0, 1.0};
  /// sphere and cylinder radius, torus major (centre-line) radius (m)
  double radius = 0.5;
  /// torus tube radius (m), < radius
  double minor_radius = 0.1;
  /// cylinder height along y (m)
  double height = 1.0;
  /// segments around a circle (sphere: around the equator; torus: around both circles), ≥ 3
  int resolution = 16;
};

/// A closed, consistently outward-oriented triangle mesh of the shape.
SurfaceMesh make_primitive(const PrimitiveShape& shape);

/// The number of triangles make_primitive() makes for the shape, counted without making them
/// (so a huge resolution can be refused first): box and plane 12; with n = resolution, sphere
/// 2n (max(2, ⌊n/2⌋) − 1), cylinder 4n, torus 2n max(3, ⌊n/2⌋). A double, so it cannot overflow.
double primitive_triangle_count(const PrimitiveShape& shape);

}  // namespace stiffsoft
