#include <stiffsoft/libfem/box_tet_mesh.hpp>

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <map>

using namespace stiffsoft::fem;

TEST(BoxTetMesh, TetsArePositiveAndFillTheBox) {
  const TetMesh mesh = box_tet_mesh({1.0, 0.2, 0.3}, {5, 2, 3});
  EXPECT_EQ(mesh.X.rows(), 6 * 3 * 4);
  EXPECT_EQ(mesh.T.rows(), 6 * 5 * 2 * 3);
  double volume = 0;
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    Eigen::Matrix3d D;
    for (int a = 0; a < 3; ++a)
      D.col(a) = (mesh.X.row(mesh.T(e, a + 1)) - mesh.X.row(mesh.T(e, 0))).transpose();
    EXPECT_GT(D.determinant(), 0.0) << "tet " << e;
    volume += D.determinant() / 6;
  }
  EXPECT_NEAR(volume, 1.0 * 0.2 * 0.3, 1e-14);
}

TEST(BoxTetMesh, IsConforming) {
  // Every triangle is shared by two tets, except the boundary ones: 2 per boundary quad.
  const int nx = 4, ny = 3, nz = 2;
  const TetMesh mesh = box_tet_mesh({1, 1, 1}, {nx, ny, nz});
  std::map<std::array<int, 3>, int> faces;
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f;
      int k = 0;
      for (int a = 0; a < 4; ++a)
        if (a != skip) f[k++] = mesh.T(e, a);
      std::sort(f.begin(), f.end());
      ++faces[f];
    }
  int boundary = 0;
  for (const auto& [face, count] : faces) {
    EXPECT_LE(count, 2);
    boundary += count == 1;
  }
  EXPECT_EQ(boundary, 2 * 2 * (nx * ny + ny * nz + nz * nx));
}

TEST(BoxTetMesh, RejectsEmptyBoxes) {
  EXPECT_THROW(box_tet_mesh({1, 0, 1}, {1, 1, 1}), std::invalid_argument);
  EXPECT_THROW(box_tet_mesh({1, 1, 1}, {1, 0, 1}), std::invalid_argument);
}
