#include <stiffsoft/meshing/primitive.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <stiffsoft/meshing/mass_moments.hpp>
#include <stiffsoft/meshing/mesh_checks.hpp>

namespace stiffsoft {
namespace {

PrimitiveShape shape(PrimitiveShape::Type type) {
  PrimitiveShape s;
  s.type = type;
  return s;
}

void expect_valid(const SurfaceMesh& mesh) {
  const auto problem = closed_manifold_problem(mesh);
  EXPECT_FALSE(problem.has_value()) << *problem;
  const auto self = find_self_intersection(mesh);
  EXPECT_FALSE(self.has_value()) << "faces " << self->first << " and " << self->second;
}

TEST(Primitive, BoxIsClosedOrientedAndHasTwelveTriangles) {
  PrimitiveShape s = shape(PrimitiveShape::Type::Box);
  s.extents = {1.0, 2.0, 3.0};
  const SurfaceMesh m = make_primitive(s);
  EXPECT_EQ(m.V.rows(), 8);
  EXPECT_EQ(m.F.rows(), 12);
  expect_valid(m);
  EXPECT_DOUBLE_EQ(m.V.col(1).maxCoeff(), 1.0);
  EXPECT_DOUBLE_EQ(m.V.col(2).minCoeff(), -1.5);
}

TEST(Primitive, PlaneIsAThinBox) {
  PrimitiveShape s = shape(PrimitiveShape::Type::Plane);
  s.extents = {10.0, 0.01, 4.0};
  const SurfaceMesh m = make_primitive(s);
  EXPECT_EQ(m.F.rows(), 12);
  expect_valid(m);
  EXPECT_NEAR(mass_moments(m).volume, 10.0 * 0.01 * 4.0, 1e-14);
}

TEST(Primitive, SphereHasPolesAndRings) {
  for (int n : {3, 4, 7, 16, 33}) {
    PrimitiveShape s = shape(PrimitiveShape::Type::Sphere);
    s.resolution = n;
    const SurfaceMesh m = make_primitive(s);
    const int rings = std::max(2, n / 2);
    EXPECT_EQ(m.V.rows(), 2 + n * (rings - 1)) << n;
    EXPECT_EQ(m.F.rows(), 2 * n * (rings - 1)) << n;
    expect_valid(m);
    EXPECT_NEAR(m.V.rowwise().norm().maxCoeff(), s.radius, 1e-15);
    EXPECT_NEAR(m.V.rowwise().norm().minCoeff(), s.radius, 1e-15);
  }
}

TEST(Primitive, CylinderVolumeIsPolygonAreaTimesHeight) {
  for (int n : {3, 8, 24}) {
    PrimitiveShape s = shape(PrimitiveShape::Type::Cylinder);
    s.resolution = n;
    s.radius = 0.3;
    s.height = 2.0;
    const SurfaceMesh m = make_primitive(s);
    EXPECT_EQ(m.F.rows(), 4 * n);
    expect_valid(m);
    const double polygon = 0.5 * n * s.radius * s.radius * std::sin(2.0 * std::numbers::pi / n);
    EXPECT_NEAR(mass_moments(m).volume, polygon * s.height, 1e-14) << n;
  }
}

TEST(Primitive, TorusVolumeMatchesItsPolyhedron) {
  for (int n : {3, 6, 16, 40}) {
    PrimitiveShape s = shape(PrimitiveShape::Type::Torus);
    s.resolution = n;
    s.radius = 1.0;
    s.minor_radius = 0.25;
    const SurfaceMesh m = make_primitive(s);
    const int tube = std::max(3, n / 2);
    EXPECT_EQ(m.F.rows(), 2 * n * tube);
    expect_valid(m);
    // Each of the n wedges sweeps the tube polygon (area A, centroid at distance R) along a chord:
    // V = n sin(2π/n) · A · R, A = (m/2) r² sin(2π/m).
    const double A = 0.5 * tube * s.minor_radius * s.minor_radius * std::sin(2.0 * std::numbers::pi / tube);
    EXPECT_NEAR(mass_moments(m).volume, n * std::sin(2.0 * std::numbers::pi / n) * A * s.radius, 1e-14) << n;
  }
}

TEST(Primitive, BadParametersThrowWithAClearMessage) {
  const auto message = [](const PrimitiveShape& s) {
    try {
      make_primitive(s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  PrimitiveShape box = shape(PrimitiveShape::Type::Box);
  box.extents = {1.0, 0.0, 1.0};
  EXPECT_NE(message(box).find("extents.y"), std::string::npos) << message(box);
  PrimitiveShape plane = shape(PrimitiveShape::Type::Plane);
  plane.extents = {1.0, -0.1, 1.0};
  EXPECT_NE(message(plane).find("thickness"), std::string::npos) << message(plane);
  PrimitiveShape sphere = shape(PrimitiveShape::Type::Sphere);
  sphere.radius = std::nan("");
  EXPECT_NE(message(sphere).find("radius"), std::string::npos) << message(sphere);
  sphere.radius = 1.0;
  sphere.resolution = 2;
  EXPECT_NE(message(sphere).find("resolution"), std::string::npos) << message(sphere);
  PrimitiveShape cylinder = shape(PrimitiveShape::Type::Cylinder);
  cylinder.height = 0.0;
  EXPECT_NE(message(cylinder).find("height"), std::string::npos) << message(cylinder);
  PrimitiveShape torus = shape(PrimitiveShape::Type::Torus);
  torus.radius = 0.5;
  torus.minor_radius = 0.5;
  EXPECT_NE(message(torus).find("minor_radius"), std::string::npos) << message(torus);
}

TEST(Primitive, TriangleCountIsCountedWithoutMakingTheMesh) {
  using Type = PrimitiveShape::Type;
  for (Type type : {Type::Box, Type::Plane, Type::Sphere, Type::Cylinder, Type::Torus})
    for (int resolution : {3, 4, 5, 16, 33}) {
      PrimitiveShape shape;
      shape.type = type;
      shape.resolution = resolution;
      EXPECT_EQ(primitive_triangle_count(shape), double(make_primitive(shape).F.rows()))
          << int(type) << " at resolution " << resolution;
    }
  PrimitiveShape huge;
  huge.type = Type::Sphere;
  huge.resolution = 2'000'000'000;
  EXPECT_DOUBLE_EQ(primitive_triangle_count(huge), 4e18 - 4e9);
}

}  // namespace
}  // namespace stiffsoft
