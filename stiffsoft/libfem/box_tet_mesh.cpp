#include <stiffsoft/libfem/box_tet_mesh.hpp>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <stdexcept>
#include <utility>

namespace stiffsoft::fem {

TetMesh box_tet_mesh(const Eigen::Vector3d& size, const Eigen::Vector3i& cells) {
  if (!(size.minCoeff() > 0) || cells.minCoeff() < 1)
    throw std::invalid_argument("libfem: box_tet_mesh needs positive sizes and at least one cell per axis");
  const int nx = cells.x(), ny = cells.y(), nz = cells.z();
  const auto node = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  TetMesh mesh;
  mesh.X.resize((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        mesh.X.row(node(i, j, k)) << size.x() * i / nx, size.y() * j / ny, size.z() * k / nz;
  // Each tet walks from corner (0,0,0) to (1,1,1) of the cell along the axes in one of 6 orders.
  constexpr std::array<std::array<int, 3>, 6> orders = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  mesh.T.resize(6 * nx * ny * nz, 4);
  int t = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& order : orders) {
          std::array<int, 3> c = {i, j, k};
          std::array<int, 4> tet;
          tet[0] = node(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[order[s]];
            tet[s + 1] = node(c[0], c[1], c[2]);
          }
          Eigen::Matrix3d D;
          for (int a = 0; a < 3; ++a) D.col(a) = (mesh.X.row(tet[a + 1]) - mesh.X.row(tet[0])).transpose();
          if (D.determinant() < 0) std::swap(tet[1], tet[2]);
          mesh.T.row(t++) << tet[0], tet[1], tet[2], tet[3];
        }
  return mesh;
}

}  // namespace stiffsoft::fem
