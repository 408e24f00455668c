#include <stiffsoft/coupling/contact/edge_edge_mollifier.hpp>

#include <Eigen/Geometry>

namespace stiffsoft::contact {

double edge_edge_mollifier_threshold(const Eigen::Vector3d& ea0_rest, const Eigen::Vector3d& ea1_rest,
                                     const Eigen::Vector3d& eb0_rest, const Eigen::Vector3d& eb1_rest) {
  return 1e-3 * (ea0_rest - ea1_rest).squaredNorm() * (eb0_rest - eb1_rest).squaredNorm();
}

double edge_edge_cross_squared_norm(const Vector12d& x) {
  const Eigen::Vector3d a = x.segment<3>(3) - x.segment<3>(0), b = x.segment<3>(9) - x.segment<3>(6);
  return a.cross(b).squaredNorm();
}

Vector12d edge_edge_cross_squared_norm_gradient(const Vector12d& x) {
  const Eigen::Vector3d a = x.segment<3>(3) - x.segment<3>(0), b = x.segment<3>(9) - x.segment<3>(6);
  const Eigen::Vector3d n = a.cross(b);
  const Eigen::Vector3d ga = 2.0 * b.cross(n), gb = 2.0 * n.cross(a);
  Vector12d g;
  g << -ga, ga, -gb, gb;
  return g;
}

Matrix12d edge_edge_cross_squared_norm_hessian(const Vector12d& x) {
  const Eigen::Vector3d a = x.segment<3>(3) - x.segment<3>(0), b = x.segment<3>(9) - x.segment<3>(6);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d Haa = 2.0 * (b.squaredNorm() * I - b * b.transpose());
  const Eigen::Matrix3d Hbb = 2.0 * (a.squaredNorm() * I - a * a.transpose());
  const Eigen::Matrix3d Hab = 2.0 * (2.0 * a * b.transpose() - b * a.transpose() - a.dot(b) * I);
  // Signs of the vertices in a and b: a = −ea0 + ea1, b = −eb0 + eb1.
  constexpr double sa[2] = {-1.0, 1.0};
  Matrix12d H;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const double sij = sa[i] * sa[j];
      H.block<3, 3>(3 * i, 3 * j) = sij * Haa;
      H.block<3, 3>(6 + 3 * i, 6 + 3 * j) = sij * Hbb;
      H.block<3, 3>(3 * i, 6 + 3 * j) = sij * Hab;
      H.block<3, 3>(6 + 3 * j, 3 * i) = sij * Hab.transpose();
    }
  return H;
}

double mollifier_of_cross(double c, double eps_x) {
  if (c >= eps_x) return 1.0;
  const double r = c / eps_x;
  return (2.0 - r) * r;
}

double edge_edge_mollifier(const Vector12d& x, double eps_x) {
  return mollifier_of_cross(edge_edge_cross_squared_norm(x), eps_x);
}

Vector12d edge_edge_mollifier_gradient(const Vector12d& x, double eps_x) {
  const double c = edge_edge_cross_squared_norm(x);
  if (c >= eps_x) return Vector12d::Zero();
  return (2.0 / eps_x - 2.0 * c / (eps_x * eps_x)) * edge_edge_cross_squared_norm_gradient(x);
}

Matrix12d edge_edge_mollifier_hessian(const Vector12d& x, double eps_x) {
  const double c = edge_edge_cross_squared_norm(x);
  if (c >= eps_x) return Matrix12d::Zero();
  const Vector12d gc = edge_edge_cross_squared_norm_gradient(x);
  return (-2.0 / (eps_x * eps_x)) * gc * gc.transpose() +
         (2.0 / eps_x - 2.0 * c / (eps_x * eps_x)) * edge_edge_cross_squared_norm_hessian(x);
}
}  // namespace stiffsoft::contact
