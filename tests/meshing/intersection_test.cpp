#include <stiffsoft/meshing/intersection.hpp>

#include <gtest/gtest.h>

#include <stiffsoft/meshing/primitive.hpp>

namespace stiffsoft {
namespace {

SurfaceMesh box(const Eigen::Vector3d& centre, const Eigen::Vector3d& extents = Eigen::Vector3d::Ones()) {
  PrimitiveShape s;
  s.extents = extents;
  SurfaceMesh m = make_primitive(s);
  m.V.rowwise() += centre.transpose();
  return m;
}

TEST(FindIntersection, FindsTwoOverlappingBoxes) {
  const auto hit = find_intersection({box({0, 0, 0}), box({0.5, 0.3, -0.2})});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->surface_a, 0);
  EXPECT_EQ(hit->surface_b, 1);
  EXPECT_GE(hit->face_a, 0);
  EXPECT_LT(hit->face_a, 12);
  EXPECT_GE(hit->face_b, 0);
  EXPECT_LT(hit->face_b, 12);
}

TEST(FindIntersection, MissesSeparatedBoxes) {
  EXPECT_FALSE(find_intersection({box({0, 0, 0}), box({1.001, 0, 0})}).has_value());
  EXPECT_FALSE(find_intersection({box({0, 0, 0}), box({1.0, 1.0, 1.0 + 1e-12})}).has_value());
  EXPECT_FALSE(find_intersection({box({0, 0, 0})}).has_value());
  EXPECT_FALSE(find_intersection({}).has_value());
}

TEST(FindIntersection, TouchingCounts) {
  EXPECT_TRUE(find_intersection({box({0, 0, 0}), box({1.0, 0, 0})}).has_value());
  EXPECT_TRUE(find_intersection({box({0, 0, 0}), box({1.0, 1.0, 1.0})}).has_value());  // corner to corner
}

TEST(FindIntersection, NamesTheRightSurfaces) {
  // 0 and 3 overlap; 1 and 2 are near 0 but apart; 4 overlaps only 3.
  const std::vector<SurfaceMesh> surfaces = {box({0, 0, 0}), box({0, 1.5, -1.5}), box({-1.2, 0, 0}),
                                             box({0.9, 0.9, 0.9}), box({1.6, 1.6, 0.9})};
  const auto hit = find_intersection(surfaces);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->surface_a, 0);
  EXPECT_EQ(hit->surface_b, 3);
  std::vector<SurfaceMesh> rest(surfaces.begin() + 1, surfaces.end());
  const auto next = find_intersection(rest);
  ASSERT_TRUE(next.has_value());
  EXPECT_EQ(next->surface_a, 2);  // boxes 3 and 4 of the full list
  EXPECT_EQ(next->surface_b, 3);
}

TEST(FindOverlap, NestedBoxesOverlapWithoutIntersecting) {
  const std::vector<SurfaceMesh> surfaces = {box({5, 0, 0}), box({0, 0, 0}, {4, 4, 4}), box({0.5, 0.2, -0.3})};
  EXPECT_FALSE(find_intersection(surfaces).has_value());
  const auto inside = find_containment(surfaces);
  ASSERT_TRUE(inside.has_value());
  EXPECT_EQ(inside->inner, 2);
  EXPECT_EQ(inside->outer, 1);
  const auto overlap = find_overlap(surfaces);
  ASSERT_TRUE(overlap.has_value());
  ASSERT_TRUE(std::holds_alternative<SurfaceContainment>(*overlap));
  const std::string message = describe(*overlap, {"far", "crate", "die"});
  EXPECT_EQ(message.rfind("'die' lies inside 'crate'", 0), 0u) << message;
}

TEST(FindOverlap, ABallInTheHoleOfATorusIsNotInside) {
  PrimitiveShape torus;
  torus.type = PrimitiveShape::Type::Torus;
  torus.radius = 1.0;
  torus.minor_radius = 0.3;
  PrimitiveShape ball;
  ball.type = PrimitiveShape::Type::Sphere;
  ball.radius = 0.2;
  const std::vector<SurfaceMesh> apart = {make_primitive(torus), make_primitive(ball)};
  EXPECT_FALSE(find_overlap(apart).has_value());
  std::vector<SurfaceMesh> in_tube = apart;
  in_tube[1].V.col(0).array() += 1.0;  // centre on the tube's centre line, radius 0.2 < 0.3
  const auto overlap = find_overlap(in_tube);
  ASSERT_TRUE(overlap.has_value());
  ASSERT_TRUE(std::holds_alternative<SurfaceContainment>(*overlap));
  EXPECT_EQ(std::get<SurfaceContainment>(*overlap).inner, 1);
  EXPECT_EQ(std::get<SurfaceContainment>(*overlap).outer, 0);
}

TEST(FindOverlap, ReportsCrossingTrianglesFirst) {
  const auto overlap = find_overlap({box({0, 0, 0}), box({0.5, 0, 0})});
  ASSERT_TRUE(overlap.has_value());
  ASSERT_TRUE(std::holds_alternative<TriangleIntersection>(*overlap));
  const std::string message = describe(*overlap, {"a"});
  EXPECT_EQ(message.rfind("'a' and surface 1 intersect: face ", 0), 0u) << message;
}

}  // namespace
}  // namespace stiffsoft
