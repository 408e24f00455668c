#pragma once
/// @file IPC's edge–edge mollifier for nearly parallel edges (Li et al. 2020, §4.3, eq. 13).
/// m(x) = m̃(c(x)) with c = ‖(ea1 − ea0) × (eb1 − eb0)‖² (m⁴) and
/// m̃(c) = (2 − c/ε_x) c/ε_x for c < ε_x, 1 otherwise (C¹ at ε_x).

#include <Eigen/Core>

#include <stiffsoft/coupling/contact/primitive_pair.hpp>

namespace stiffsoft::contact {

/// ε_x = 1e-3 ‖ea0 − ea1‖² ‖eb0 − eb1‖² from the REST positions of the two edges, m⁴.
inline double edge_edge_mollifier_threshold(const Eigen::Vector3d& ea0_rest, const Eigen::Vector3d& ea1_rest,
                                            const Eigen::Vector3d& eb0_rest, const Eigen::Vector3d& eb1_rest) {
  return 1e-3 * (ea0_rest - ea1_rest).squaredNorm() * (eb0_rest - eb1_rest).squaredNorm();
}

/// c(x) = ‖(ea1 − ea0) × (eb1 − eb0)‖² of an EE stencil [ea0; ea1; eb0; eb1], m⁴.
inline double edge_edge_cross_squared_norm(const Vector12d& x) {
  const Eigen::Vector3d a = x.segment<3>(3) - x.segment<3>(0), b = x.segment<3>(9) - x.segment<3>(6);
  return a.cross(b).squaredNorm();
}

/// ∇c, 12-vector: ∂c/∂a = 2 b × n, ∂c/∂b = 2 n × a with n = a × b, a = ea1 − ea0, b = eb1 − eb0.
inline Vector12d edge_edge_cross_squared_norm_gradient(const Vector12d& x) {
  const Eigen::Vector3d a = x.segment<3>(3) - x.segment<3>(0), b = x.segment<3>(9) - x.segment<3>(6);
  const Eigen::Vector3d n = a.cross(b);
  const Eigen::Vector3d ga = 2.0 * b.cross(n), gb = 2.0 * n.cross(a);
  Vector12d g;
  g << -ga, ga, -gb, gb;
  return g;
}

/// ∇²c, 12×12, from ∂²c/∂a² = 2(‖b‖² I − b bᵀ), ∂²c/∂b² = 2(‖a‖² I − a aᵀ),
/// ∂²c/∂a∂b = 2(2 a bᵀ − b aᵀ − (a·b) I), chained through a = ea1 − ea0, b = eb1 − eb0.
inline Matrix12d edge_edge_cross_squared_norm_hessian(const Vector12d& x) {
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

/// m̃(c) = (2 − c/ε_x) c/ε_x for c < ε_x, else 1; dimensionless.
inline double mollifier_of_cross(double c, double eps_x) {
  if (c >= eps_x) return 1.0;
  const double r = c / eps_x;
  return (2.0 - r) * r;
}

/// Edge–edge mollifier m(x) = m̃(c(x)) of an EE stencil [ea0; ea1; eb0; eb1]; eps_x in m⁴, > 0.
inline double edge_edge_mollifier(const Vector12d& x, double eps_x) {
  return mollifier_of_cross(edge_edge_cross_squared_norm(x), eps_x);
}

/// ∇m = m̃'(c) ∇c with m̃'(c) = 2/ε_x − 2c/ε_x² (c < ε_x), else zero; 12-vector, 1/m.
inline Vector12d edge_edge_mollifier_gradient(const Vector12d& x, double eps_x) {
  const double c = edge_edge_cross_squared_norm(x);
  if (c >= eps_x) return Vector12d::Zero();
  return (2.0 / eps_x - 2.0 * c / (eps_x * eps_x)) * edge_edge_cross_squared_norm_gradient(x);
}

/// ∇²m = m̃''(c) ∇c ∇cᵀ + m̃'(c) ∇²c with m̃'' = −2/ε_x² (c < ε_x), else zero; 12×12, 1/m².
inline Matrix12d edge_edge_mollifier_hessian(const Vector12d& x, double eps_x) {
  const double c = edge_edge_cross_squared_norm(x);
  if (c >= eps_x) return Matrix12d::Zero();
  const Vector12d gc = edge_edge_cross_squared_norm_gradient(x);
  return (-2.0 / (eps_x * eps_x)) * gc * gc.transpose() +
         (2.0 / eps_x - 2.0 * c / (eps_x * eps_x)) * edge_edge_cross_squared_norm_hessian(x);
}

}  // namespace stiffsoft::contact
