#include "peers/ring_links.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace stiffsoft::peers {

int linking_number(const Eigen::MatrixX3d& A, const Eigen::MatrixX3d& B) {
  const Eigen::Index n = A.rows();
  const Eigen::Vector3d centre = A.colwise().mean().transpose();
  // Plane normal of A (Newell's method: robust for any planar polygon).
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d a = A.row(i).transpose(), b = A.row((i + 1) % n).transpose();
    normal += (a - centre).cross(b - centre);
  }
  normal.normalize();
  int crossings = 0;
  for (Eigen::Index s = 0; s < B.rows(); ++s) {
    const Eigen::Vector3d p = B.row(s).transpose(), q = B.row((s + 1) % B.rows()).transpose();
    const double dp = normal.dot(p - centre), dq = normal.dot(q - centre);
    if ((dp > 0) == (dq > 0) || dp == dq) continue;
    const Eigen::Vector3d x = p + (dp / (dp - dq)) * (q - p);  // where the segment meets A's plane
    // Inside the convex polygon: on the same side of every edge as the orientation says.
    bool inside = true;
    for (Eigen::Index i = 0; i < n && inside; ++i) {
      const Eigen::Vector3d a = A.row(i).transpose(), b = A.row((i + 1) % n).transpose();
      inside = normal.dot((b - a).cross(x - a)) > 0;
    }
    if (inside) crossings += dp < 0 ? 1 : -1;
  }
  return crossings;
}

}  // namespace stiffsoft::peers
