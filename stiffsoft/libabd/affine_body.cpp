#include <stiffsoft/libabd/affine_body.hpp>

#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace stiffsoft::abd {

Jacobian jacobian(const Eigen::Vector3d& x_bar) {
  Jacobian J = Jacobian::Zero();
  J.leftCols<3>().setIdentity();
  for (int i = 0; i < 3; ++i) J.block<1, 3>(i, 3 + 3 * i) = x_bar.transpose();
  return J;
}

Eigen::Matrix3d affine_matrix(const Vector12d& q) {
  Eigen::Matrix3d A;
  for (int i = 0; i < 3; ++i) A.row(i) = q.segment<3>(3 + 3 * i).transpose();
  return A;
}

Vector12d make_q(const Eigen::Vector3d& p, const Eigen::Matrix3d& A) {
  Vector12d q;
  q.head<3>() = p;
  for (int i = 0; i < 3; ++i) q.segment<3>(3 + 3 * i) = A.row(i).transpose();
  return q;
}

static Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& w) {
  Eigen::Matrix3d W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return W;
}

Vector12d rigid_velocity(const Vector12d& q, const Eigen::Vector3d& v,
                         const Eigen::Vector3d& omega) {
  return make_q(v, cross_matrix(omega) * affine_matrix(q));
}

Eigen::Vector3d angular_velocity(const Vector12d& q, const Vector12d& qdot) {
  const Eigen::Matrix3d W = affine_matrix(qdot) * affine_matrix(q).inverse();
  return 0.5 * Eigen::Vector3d(W(2, 1) - W(1, 2), W(0, 2) - W(2, 0), W(1, 0) - W(0, 1));
}

Vector12d rigid_motion(const Vector12d& q, const Eigen::Vector3d& v, const Eigen::Vector3d& omega,
                       double t) {
  const double angle = omega.norm() * t;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  if (angle > 0) R = Eigen::AngleAxisd(angle, omega.normalized()).toRotationMatrix();
  return make_q(translation(q) + v * t, R * affine_matrix(q));
}

Eigen::Matrix3d closest_rotation(const Eigen::Matrix3d& A) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0) U.col(2) *= -1;
  return U * V.transpose();
}

}  // namespace stiffsoft::abd
