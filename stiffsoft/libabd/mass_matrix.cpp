#include <stiffsoft/libabd/mass_matrix.hpp>

namespace stiffsoft::abd {

MassProperties mass_properties(double volume, const Eigen::Vector3d& first,
                               const Eigen::Matrix3d& second, double density) {
  return {density * volume, density * first, density * second};
}

Matrix12d mass_matrix(const MassProperties& mp) {
  Matrix12d M = Matrix12d::Zero();
  M.topLeftCorner<3, 3>() = mp.mass * Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i) {
    M.block<1, 3>(i, 3 + 3 * i) = mp.first.transpose();
    M.block<3, 1>(3 + 3 * i, i) = mp.first;
    M.block<3, 3>(3 + 3 * i, 3 + 3 * i) = mp.second;
  }
  return M;
}

Eigen::Matrix3d inertia_tensor(const MassProperties& mp) {
  return mp.second.trace() * Eigen::Matrix3d::Identity() - mp.second;
}

}  // namespace stiffsoft::abd
