#include <stiffsoft/meshing/tet_boundary.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <stdexcept>
#include <string>

#include <stiffsoft/meshing/mass_moments.hpp>
#include <stiffsoft/meshing/mesh_checks.hpp>

namespace stiffsoft {
namespace {

TetMesh two_tets() {
  TetMesh m;
  m.X.resize(6, 3);
  m.X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 7, 7, 7;  // node 5: used by no tet here
  m.T.resize(2, 4);
  m.T << 0, 1, 2, 3, 1, 2, 3, 4;
  return m;
}

TEST(TetBoundary, OneTetGivesFourOutwardFaces) {
  TetMesh m;
  m.X.resize(4, 3);
  m.X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.T.resize(1, 4);
  m.T << 0, 1, 2, 3;
  const TetBoundary b = boundary_surface(m);
  EXPECT_EQ(b.surface.F.rows(), 4);
  EXPECT_EQ(b.E.rows(), 6);
  EXPECT_FALSE(closed_manifold_problem(b.surface).has_value()) << *closed_manifold_problem(b.surface);
  EXPECT_DOUBLE_EQ(mass_moments(b.surface).volume, 1.0 / 6.0);
  // Each face's normal points away from the node it leaves out.
  for (Eigen::Index f = 0; f < 4; ++f) {
    const Eigen::Vector3d a = b.surface.V.row(b.surface.F(f, 0)), c = b.surface.V.row(b.surface.F(f, 1)),
                          d = b.surface.V.row(b.surface.F(f, 2));
    Eigen::Vector3d opposite = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) opposite += m.X.row(k).transpose();
    opposite -= a + c + d;  // the fourth node
    EXPECT_LT((c - a).cross(d - a).dot(opposite - a), 0.0) << "face " << f;
  }
}

TEST(TetBoundary, SharedFaceIsInteriorAndVerticesMapToNodes) {
  const TetBoundary b = boundary_surface(two_tets());
  EXPECT_EQ(b.surface.F.rows(), 6);  // 8 faces, the shared one twice
  EXPECT_EQ(b.node_of_vertex, (Eigen::VectorXi(5) << 0, 1, 2, 3, 4).finished());  // node 5 is not on it
  EXPECT_EQ(b.surface.V, two_tets().X.topRows(5));
  EXPECT_EQ(b.E, edges(b.surface.F));
  EXPECT_EQ(b.E.rows(), 9);  // V − E + F = 2: 5 − 9 + 6
  EXPECT_EQ(b.tet_of_face, (Eigen::VectorXi(6) << 0, 0, 0, 1, 1, 1).finished());
  EXPECT_FALSE(closed_manifold_problem(b.surface).has_value()) << *closed_manifold_problem(b.surface);
  EXPECT_DOUBLE_EQ(mass_moments(b.surface).volume, 0.5);
}

TEST(TetBoundary, FaceInThreeTetsIsNotManifold) {
  TetMesh m = two_tets();
  m.X.row(5) << -1, -1, -1;
  m.T.conservativeResize(3, 4);
  m.T.row(2) << 5, 1, 2, 3;  // a third tet on face (1, 2, 3), overlapping the first
  try {
    boundary_surface(m, "body 'blob'");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("body 'blob': triangle (1, 2, 3) belongs to 3 tetrahedra"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace stiffsoft
