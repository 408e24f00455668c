#include <stiffsoft/meshing/mesh_checks.hpp>

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include <stiffsoft/meshing/primitive.hpp>

namespace stiffsoft {
namespace {

SurfaceMesh box(const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  SurfaceMesh m = make_primitive(PrimitiveShape{});
  m.V.rowwise() += centre.transpose();
  return m;
}

SurfaceMesh merge(const SurfaceMesh& a, const SurfaceMesh& b) {
  SurfaceMesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V;
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + static_cast<int>(a.V.rows())).matrix();
  return m;
}

std::string closed_error(const SurfaceMesh& m, const std::string& what) {
  try {
    check_closed_manifold(m, what);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no exception";
}

TEST(CheckClosedManifold, AcceptsABoxAndTwoSeparateBoxes) {
  EXPECT_NO_THROW(check_closed_manifold(box(), "box"));
  EXPECT_NO_THROW(check_closed_manifold(merge(box(), box({3.0, 0.0, 0.0})), "two boxes"));
}

TEST(CheckClosedManifold, AnOpenMeshNamesTheBodyAndTheBoundaryEdge) {
  SurfaceMesh m = box();
  m.F.conservativeResize(11, 3);  // drop one triangle
  const std::string e = closed_error(m, "crate.obj");
  EXPECT_EQ(e.rfind("crate.obj: edge (", 0), 0u) << e;
  EXPECT_NE(e.find("not closed"), std::string::npos) << e;
}

TEST(CheckClosedManifold, AFlippedFaceIsInconsistentlyOriented) {
  SurfaceMesh m = box();
  std::swap(m.F(4, 1), m.F(4, 2));
  const std::string e = closed_error(m, "crate");
  EXPECT_NE(e.find("not consistently oriented"), std::string::npos) << e;
  EXPECT_TRUE(e.find("faces 4 and") != std::string::npos || e.find(" and 4:") != std::string::npos) << e;
}

TEST(CheckClosedManifold, AnInsideOutBoxHasNegativeVolume) {
  SurfaceMesh m = box();
  m.F.col(1).swap(m.F.col(2));
  const std::string e = closed_error(m, "crate");
  EXPECT_NE(e.find("oriented inward"), std::string::npos) << e;
}

TEST(CheckClosedManifold, ThreeFacesOnAnEdgeAreNotManifold) {
  SurfaceMesh m = box();
  m.F.conservativeResize(13, 3);
  m.F.row(12) = m.F.row(0);
  const std::string e = closed_error(m, "crate");
  EXPECT_NE(e.find("not manifold"), std::string::npos) << e;
}

TEST(CheckClosedManifold, TwoTetrahedraSharingAVertexAreNotManifold) {
  SurfaceMesh m;
  m.V.resize(7, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1;
  m.F.resize(8, 3);
  // tet (0,1,2,3) and its point reflection (0,4,5,6), both outward
  m.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 5, 4, 0, 4, 6, 0, 6, 5, 4, 5, 6;
  const std::string e = closed_error(m, "bow tie");
  EXPECT_NE(e.find("vertex 0 is not manifold"), std::string::npos) << e;
}

TEST(CheckClosedManifold, DegenerateAndOutOfRangeFacesAreReported) {
  SurfaceMesh m = box();
  m.V.row(m.F(3, 2)) = 0.5 * (m.V.row(m.F(3, 0)) + m.V.row(m.F(3, 1)));
  EXPECT_NE(closed_error(m, "crate").find("zero area"), std::string::npos) << closed_error(m, "crate");
  m = box();
  m.F(5, 1) = m.F(5, 0);
  EXPECT_NE(closed_error(m, "crate").find("face 5"), std::string::npos) << closed_error(m, "crate");
  m = box();
  m.F(2, 2) = 8;
  EXPECT_NE(closed_error(m, "crate").find("out of range"), std::string::npos) << closed_error(m, "crate");
  EXPECT_NE(closed_error(SurfaceMesh{}, "nothing").find("no faces"), std::string::npos);
}

std::string self_error(const SurfaceMesh& m, const std::string& what) {
  try {
    check_not_self_intersecting(m, what);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no exception";
}

TEST(CheckNotSelfIntersecting, TwoOverlappingBoxesInOneMeshIntersect) {
  const SurfaceMesh m = merge(box(), box({0.5, 0.25, 0.1}));
  EXPECT_NO_THROW(check_closed_manifold(m, "merged"));  // closed and manifold, yet invalid
  const std::string e = self_error(m, "merged.obj");
  EXPECT_EQ(e.rfind("merged.obj: the surface intersects itself: face ", 0), 0u) << e;
  const auto pair = find_self_intersection(m);
  ASSERT_TRUE(pair.has_value());
  EXPECT_LT(pair->first, 12);  // one face from each box
  EXPECT_GE(pair->second, 12);
}

TEST(CheckNotSelfIntersecting, SeparateAndTouchingBoxes) {
  EXPECT_FALSE(find_self_intersection(merge(box(), box({1.5, 0.0, 0.0}))).has_value());
  // Two boxes meeting face to face (distinct vertices at x = 0.5) touch, which counts.
  EXPECT_TRUE(find_self_intersection(merge(box(), box({1.0, 0.0, 0.0}))).has_value());
}

TEST(CheckNotSelfIntersecting, PrimitivesDoNotIntersectThemselves) {
  for (auto type : {PrimitiveShape::Type::Box, PrimitiveShape::Type::Sphere, PrimitiveShape::Type::Cylinder,
                    PrimitiveShape::Type::Torus, PrimitiveShape::Type::Plane}) {
    PrimitiveShape s;
    s.type = type;
    s.extents = {1.0, 0.02, 1.0};
    EXPECT_NO_THROW(check_not_self_intersecting(make_primitive(s), "primitive"));
  }
}

SurfaceMesh two_triangles(const Eigen::Matrix<double, Eigen::Dynamic, 3>& V, const Eigen::Matrix<int, 2, 3>& F) {
  SurfaceMesh m;
  m.V = V;
  m.F = F;
  return m;
}

TEST(CheckNotSelfIntersecting, NeighboursCountOnlyBeyondWhatTheyShare) {
  Eigen::Matrix<double, 5, 3> V;
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5, 0.5, 1, 0.4, 0.3, -1;
  // Sharing vertex 0 only.
  Eigen::Matrix<int, 2, 3> F;
  F << 0, 1, 2, 0, 3, 4;  // (0, 3, 4) crosses the plane z = 0 through the inside of (0, 1, 2)
  EXPECT_TRUE(find_self_intersection(two_triangles(V, F)).has_value());
  F << 0, 3, 4, 0, 1, 2;  // the same pair, listed the other way round
  EXPECT_TRUE(find_self_intersection(two_triangles(V, F)).has_value());
  F << 0, 1, 2, 0, 3, 4;
  V.row(4) << -1.5, -1.5, -1;  // now it crosses z = 0 outside (0, 1, 2), along (0, 0, 0)–(-0.5, -0.5, 0)
  EXPECT_FALSE(find_self_intersection(two_triangles(V, F)).has_value());
  // Sharing an edge: folded flat onto each other vs. a proper hinge.
  V.row(3) << 0.2, 0.2, 0;  // same side of edge 1–2 as vertex 0, same plane
  F << 0, 1, 2, 2, 1, 3;
  EXPECT_TRUE(find_self_intersection(two_triangles(V, F)).has_value());
  V.row(3) << 1, 1, 0;  // opposite side, same plane: a flat hinge
  EXPECT_FALSE(find_self_intersection(two_triangles(V, F)).has_value());
  V.row(3) << 0.2, 0.2, 0.1;  // folded but not coplanar
  EXPECT_FALSE(find_self_intersection(two_triangles(V, F)).has_value());
  // Sharing one vertex, coplanar, wedges overlapping: t2 = (0, 3, 4) inside the wedge of t1.
  V.row(3) << 0.1, 0.05, 0;
  V.row(4) << 0.05, 0.1, 0;
  F << 0, 1, 2, 0, 3, 4;
  EXPECT_TRUE(find_self_intersection(two_triangles(V, F)).has_value());
  V.row(3) << -0.1, -0.05, 0;  // wedges on opposite sides of vertex 0
  V.row(4) << -0.05, -0.1, 0;
  EXPECT_FALSE(find_self_intersection(two_triangles(V, F)).has_value());
}

}  // namespace
}  // namespace stiffsoft
