#include <stiffsoft/meshing/primitive.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace stiffsoft {
namespace {

// Collects vertices and triangles; quads are split along their a–c diagonal.
struct MeshBuilder {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;

  int vertex(double x, double y, double z) {
    vertices.emplace_back(x, y, z);
    return static_cast<int>(vertices.size()) - 1;
  }
  void triangle(int a, int b, int c) { triangles.emplace_back(a, b, c); }
  /// a→b→c→d counter-clockwise seen from outside
  void quad(int a, int b, int c, int d) {
    triangle(a, b, c);
    triangle(a, c, d);
  }
  SurfaceMesh mesh() const {
    SurfaceMesh m;
    m.V.resize(static_cast<Eigen::Index>(vertices.size()), 3);
    m.F.resize(static_cast<Eigen::Index>(triangles.size()), 3);
    for (size_t i = 0; i < vertices.size(); ++i) m.V.row(static_cast<Eigen::Index>(i)) = vertices[i];
    for (size_t i = 0; i < triangles.size(); ++i) m.F.row(static_cast<Eigen::Index>(i)) = triangles[i];
    return m;
  }
};

void require_positive(double value, const char* what) {
  // `!(value > 0)` also rejects NaN.
  if (!(value > 0.0) || !std::isfinite(value))
    throw std::invalid_argument(std::string("primitive: ") + what + " must be a positive finite number, got " +
                                std::to_string(value));
}

void require_resolution(int resolution, const char* shape) {
  if (resolution < 3)
    throw std::invalid_argument(std::string("primitive ") + shape + ": resolution must be >= 3, got " +
                                std::to_string(resolution));
}

SurfaceMesh make_box(const Eigen::Vector3d& extents) {
  const Eigen::Vector3d h = 0.5 * extents;
  MeshBuilder b;
  // corner index = x bit | y bit << 1 | z bit << 2
  for (int i = 0; i < 8; ++i) b.vertex((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  b.quad(0, 4, 6, 2);  // -x
  b.quad(1, 3, 7, 5);  // +x
  b.quad(0, 1, 5, 4);  // -y
  b.quad(2, 6, 7, 3);  // +y
  b.quad(0, 2, 3, 1);  // -z
  b.quad(4, 5, 7, 6);  // +z
  return b.mesh();
}

// p(θ, φ) = r (sin θ cos φ, cos θ, sin θ sin φ); the outward normal is ∂p/∂φ × ∂p/∂θ, so a quad
// (i, j) → (i, j+1) → (i+1, j+1) → (i+1, j) is counter-clockwise from outside.
SurfaceMesh make_sphere(double r, int n) {
  const int rings = std::max(2, n / 2);  // latitude bands; rings - 1 circles of n vertices
  MeshBuilder b;
  const int north = b.vertex(0.0, r, 0.0);
  for (int i = 1; i < rings; ++i) {
    const double theta = std::numbers::pi * i / rings;
    for (int j = 0; j < n; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / n;
      b.vertex(r * std::sin(theta) * std::cos(phi), r * std::cos(theta), r * std::sin(theta) * std::sin(phi));
    }
  }
  const int south = b.vertex(0.0, -r, 0.0);
  const auto at = [n](int ring, int j) { return 1 + (ring - 1) * n + (j % n); };  // ring in [1, rings)
  for (int j = 0; j < n; ++j) {
    b.triangle(north, at(1, j + 1), at(1, j));
    for (int i = 1; i + 1 < rings; ++i) b.quad(at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
    b.triangle(at(rings - 1, j), at(rings - 1, j + 1), south);
  }
  return b.mesh();
}

// p(y, φ) = (r cos φ, y, r sin φ); outward normal ∂p/∂y × ∂p/∂φ. Caps are fans around a centre vertex.
SurfaceMesh make_cylinder(double r, double height, int n) {
  MeshBuilder b;
  const double h = 0.5 * height;
  for (int j = 0; j < n; ++j) {
    const double phi = 2.0 * std::numbers::pi * j / n;
    b.vertex(r * std::cos(phi), -h, r * std::sin(phi));
    b.vertex(r * std::cos(phi), h, r * std::sin(phi));
  }
  const int bottom_centre = b.vertex(0.0, -h, 0.0);
  const int top_centre = b.vertex(0.0, h, 0.0);
  const auto bottom = [n](int j) { return 2 * (j % n); };
  const auto top = [n](int j) { return 2 * (j % n) + 1; };
  for (int j = 0; j < n; ++j) {
    b.quad(bottom(j), top(j), top(j + 1), bottom(j + 1));
    b.triangle(top_centre, top(j + 1), top(j));
    b.triangle(bottom_centre, bottom(j), bottom(j + 1));
  }
  return b.mesh();
}

// p(φ, ψ) = ((R + r cos ψ) cos φ, r sin ψ, (R + r cos ψ) sin φ); outward normal ∂p/∂ψ × ∂p/∂φ.
SurfaceMesh make_torus(double R, double r, int n) {
  const int m = std::max(3, n / 2);  // segments around the tube
  MeshBuilder b;
  for (int j = 0; j < n; ++j) {
    const double phi = 2.0 * std::numbers::pi * j / n;
    for (int k = 0; k < m; ++k) {
      const double psi = 2.0 * std::numbers::pi * k / m;
      const double rho = R + r * std::cos(psi);
      b.vertex(rho * std::cos(phi), r * std::sin(psi), rho * std::sin(phi));
    }
  }
  const auto at = [n, m](int j, int k) { return (j % n) * m + (k % m); };
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < m; ++k) b.quad(at(j, k), at(j, k + 1), at(j + 1, k + 1), at(j + 1, k));
  return b.mesh();
}

}  // namespace

double primitive_triangle_count(const PrimitiveShape& shape) {
  using Type = PrimitiveShape::Type;
  const double n = shape.resolution;
  switch (shape.type) {
    case Type::Box:
    case Type::Plane: return 12;
    case Type::Sphere: return 2 * n * (std::max(2, shape.resolution / 2) - 1);
    case Type::Cylinder: return 4 * n;
    case Type::Torus: return 2 * n * std::max(3, shape.resolution / 2);
  }
  return 0;
}

SurfaceMesh make_primitive(const PrimitiveShape& shape) {
  using Type = PrimitiveShape::Type;
  switch (shape.type) {
    case Type::Box:
    case Type::Plane: {
      const char* names[3] = {"extents.x", "extents.y", "extents.z"};
      const char* plane_names[3] = {"extents.x (size)", "extents.y (thickness)", "extents.z (size)"};
      for (int d = 0; d < 3; ++d) require_positive(shape.extents[d], shape.type == Type::Box ? names[d] : plane_names[d]);
      return make_box(shape.extents);
    }
    case Type::Sphere:
      require_positive(shape.radius, "sphere radius");
      require_resolution(shape.resolution, "sphere");
      return make_sphere(shape.radius, shape.resolution);
    case Type::Cylinder:
      require_positive(shape.radius, "cylinder radius");
      require_positive(shape.height, "cylinder height");
      require_resolution(shape.resolution, "cylinder");
      return make_cylinder(shape.radius, shape.height, shape.resolution);
    case Type::Torus:
      require_positive(shape.radius, "torus radius (major)");
      require_positive(shape.minor_radius, "torus minor_radius");
      if (!(shape.minor_radius < shape.radius))
        throw std::invalid_argument("primitive torus: minor_radius (" + std::to_string(shape.minor_radius) +
                                    ") must be smaller than radius (" + std::to_string(shape.radius) + ")");
      require_resolution(shape.resolution, "torus");
      return make_torus(shape.radius, shape.minor_radius, shape.resolution);
  }
  throw std::invalid_argument("primitive: unknown shape type");
}

}  // namespace stiffsoft
