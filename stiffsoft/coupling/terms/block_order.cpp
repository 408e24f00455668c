#include <stiffsoft/coupling/terms/block_order.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace stiffsoft {

std::vector<int> blocks_along_widest_axis(const Model& model, const Eigen::VectorXd& q) {
  const std::size_t n = model.blocks.size();
  constexpr double kFar = std::numeric_limits<double>::infinity();
  // A coordinate that is not finite (a diverged run) sorts last: the order only shapes the work.
  const auto coordinate = [&](std::size_t b, int axis) {
    const double v = q[model.blocks[b].offset + axis];
    return std::isfinite(v) ? v : kFar;
  };
  Eigen::Array3d lo = Eigen::Array3d::Constant(kFar), hi = Eigen::Array3d::Constant(-kFar);
  for (std::size_t b = 0; b < n; ++b)
    for (int axis = 0; axis < 3; ++axis) {
      const double v = coordinate(b, axis);
      if (v == kFar) continue;
      lo[axis] = std::min(lo[axis], v);
      hi[axis] = std::max(hi[axis], v);
    }
  int widest = 0;
  if (n > 0) (hi - lo).maxCoeff(&widest);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const double ka = coordinate(std::size_t(a), widest), kb = coordinate(std::size_t(b), widest);
    return ka < kb || (ka == kb && a < b);
  });
  std::vector<int> rank(n);
  for (std::size_t i = 0; i < n; ++i) rank[std::size_t(order[i])] = int(i);
  return rank;
}

}  // namespace stiffsoft
