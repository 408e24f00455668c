#include <stiffsoft/meshing/tet_mesh.hpp>

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace stiffsoft {
namespace {

/// Two tetrahedra sharing the face (1, 2, 3): the corner tet of the unit cube and the one above its
/// oblique face; volumes 1/6 and 1/3.
TetMesh two_tets() {
  TetMesh m;
  m.X.resize(5, 3);
  m.X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  m.T.resize(2, 4);
  m.T << 0, 1, 2, 3, 1, 2, 3, 4;
  m.node_sets["origin"] = {0};
  return m;
}

std::string problem(const TetMesh& m) { return tet_mesh_problem(m).value_or("none"); }

TEST(TetMesh, SignedVolumesOfTwoTets) {
  const TetMesh m = two_tets();
  EXPECT_DOUBLE_EQ(tet_signed_volume(m, 0), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(tet_signed_volume(m, 1), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(tet_mesh_volume(m), 0.5);
  EXPECT_FALSE(tet_mesh_problem(m).has_value()) << problem(m);
}

TEST(TetMesh, InvertedTetIsReportedByIndexAndReoriented) {
  TetMesh m = two_tets();
  std::swap(m.T(1, 0), m.T(1, 3));
  EXPECT_NE(problem(m).find("tetrahedron 1 (4, 2, 3, 1) is inverted"), std::string::npos) << problem(m);
  try {
    check_tet_mesh(m, "body 'jelly'");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("body 'jelly': tetrahedron 1", 0), 0u) << e.what();
  }
  EXPECT_EQ(orient_tets_positively(m), 1);
  EXPECT_GT(tet_signed_volume(m, 1), 0.0);
  EXPECT_FALSE(tet_mesh_problem(m).has_value()) << problem(m);
}

TEST(TetMesh, DegenerateTetsAreRejected) {
  TetMesh flat = two_tets();
  flat.X.row(4) << 1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0;  // on the plane x + y + z = 1 of nodes 1, 2, 3
  EXPECT_NE(problem(flat).find("tetrahedron 1"), std::string::npos) << problem(flat);
  EXPECT_NE(problem(flat).find("degenerate"), std::string::npos) << problem(flat);

  TetMesh repeated = two_tets();
  repeated.T(1, 3) = 1;
  EXPECT_NE(problem(repeated).find("tetrahedron 1 (1, 2, 3, 1) repeats a node"), std::string::npos)
      << problem(repeated);

  // Just above the tolerance: 1e-12 · ℓ̄³ with ℓ̄ ≈ 1 is 1e-12 m³; a height of 1e-9 gives ~1e-10 m³.
  TetMesh thin = two_tets();
  thin.X.row(4) = Eigen::RowVector3d(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0) + 1e-9 * Eigen::RowVector3d(1, 1, 1);
  EXPECT_FALSE(tet_mesh_problem(thin).has_value()) << problem(thin);
}

TEST(TetMesh, IndexAndNodeSetErrorsNameWhatIsWrong) {
  TetMesh m = two_tets();
  m.T(0, 2) = 7;
  EXPECT_NE(problem(m).find("tetrahedron 0 (0, 1, 7, 3) has node index 7 out of range [0, 5)"),
            std::string::npos)
      << problem(m);

  m = two_tets();
  m.node_sets["top"] = {4, 2};
  EXPECT_NE(problem(m).find("node set 'top' is not sorted"), std::string::npos) << problem(m);
  m.node_sets["top"] = {9};
  EXPECT_NE(problem(m).find("node set 'top' has node index 9"), std::string::npos) << problem(m);

  m = two_tets();
  m.X(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(problem(m).find("node 2 has a non-finite coordinate"), std::string::npos) << problem(m);

  EXPECT_EQ(problem(TetMesh{}), "has no tetrahedra");
}

TEST(TetMesh, UnreferencedNodesAreRejectedThenRemoved) {
  TetMesh m = two_tets();
  // Insert an unused node at index 2: everything from the old node 2 on moves up by one.
  m.X.conservativeResize(6, 3);
  m.X.row(5) = m.X.row(4);
  m.X.row(4) = m.X.row(3);
  m.X.row(3) = m.X.row(2);
  m.X.row(2) << 9, 9, 9;
  for (Eigen::Index t = 0; t < 2; ++t)
    for (int k = 0; k < 4; ++k)
      if (m.T(t, k) >= 2) ++m.T(t, k);
  m.node_sets["with_unused"] = {2, 5};
  EXPECT_NE(problem(m).find("node 2 is used by no tetrahedron"), std::string::npos) << problem(m);

  EXPECT_EQ(remove_unreferenced_nodes(m), 1);
  const TetMesh expected = two_tets();
  EXPECT_EQ(m.X, expected.X);
  EXPECT_EQ(m.T, expected.T);
  EXPECT_EQ(m.node_sets.at("with_unused"), std::vector<int>{4});
  EXPECT_EQ(m.node_sets.at("origin"), std::vector<int>{0});
  EXPECT_FALSE(tet_mesh_problem(m).has_value()) << problem(m);
  EXPECT_EQ(remove_unreferenced_nodes(m), 0);
}

}  // namespace
}  // namespace stiffsoft
