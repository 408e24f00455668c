#include <stiffsoft/meshing/surface_mesh.hpp>

#include <algorithm>
#include <utility>
#include <vector>

namespace stiffsoft {

Eigen::MatrixX2i edges(const Eigen::MatrixX3i& F) {
  std::vector<std::pair<int, int>> e;
  e.reserve(3 * F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      e.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  Eigen::MatrixX2i E(e.size(), 2);
  for (size_t i = 0; i < e.size(); ++i) E.row(i) << e[i].first, e[i].second;
  return E;
}

}  // namespace stiffsoft
