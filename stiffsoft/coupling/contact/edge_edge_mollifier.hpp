#pragma once
/// @file IPC's edge–edge mollifier for nearly parallel edges (Li et al. 2020, §4.3, eq. 13).
/// m(x) = m̃(c(x)) with c = ‖(ea1 − ea0) × (eb1 − eb0)‖² (m⁴) and
/// m̃(c) = (2 − c/ε_x) c/ε_x for c < ε_x, 1 otherwise (C¹ at ε_x).

#include <Eigen/Core>

#include <stiffsoft/coupling/contact/primitive_pair.hpp>

namespace stiffsoft::contact {

/// ε_x = 1e-3 ‖ea0 − ea1‖² ‖eb0 − eb1‖² from the REST positions of the two edges, m⁴.
double edge_edge_mollifier_threshold(const Eigen::Vector3d& ea0_rest, const Eigen::Vector3d& ea1_rest,
                                     const Eigen::Vector3d& eb0_rest, const Eigen::Vector3d& eb1_rest);

/// c(x) = ‖(ea1 − ea0) × (eb1 − eb0)‖² of an EE stencil [ea0; ea1; eb0; eb1], m⁴.
double edge_edge_cross_squared_norm(const Vector12d& x);

/// ∇c, 12-vector: ∂c/∂a = 2 b × n, ∂c/∂b = 2 n × a with n = a × b, a = ea1 − ea0, b = eb1 − eb0.
Vector12d edge_edge_cross_squared_norm_gradient(const Vector12d& x);

/// ∇²c, 12×12, from ∂²c/∂a² = 2(‖b‖² I − b bᵀ), ∂²c/∂b² = 2(‖a‖² I − a aᵀ),
/// ∂²c/∂a∂b = 2(2 a bᵀ − b aᵀ − (a·b) I), chained through a = ea1 − ea0, b = eb1 − eb0.
Matrix12d edge_edge_cross_squared_norm_hessian(const Vector12d& x);

/// m̃(c) = (2 − c/ε_x) c/ε_x for c < ε_x, else 1; dimensionless.
double mollifier_of_cross(double c, double eps_x);

/// Edge–edge mollifier m(x) = m̃(c(x)) of an EE stencil [ea0; ea1; eb0; eb1]; eps_x in m⁴, > 0.
double edge_edge_mollifier(const Vector12d& x, double eps_x);

/// ∇m = m̃'(c) ∇c with m̃'(c) = 2/ε_x − 2c/ε_x² (c < ε_x), else zero; 12-vector, 1/m.
Vector12d edge_edge_mollifier_gradient(const Vector12d& x, double eps_x);

/// ∇²m = m̃''(c) ∇c ∇cᵀ + m̃'(c) ∇²c with m̃'' = −2/ε_x² (c < ε_x), else zero; 12×12, 1/m².
Matrix12d edge_edge_mollifier_hessian(const Vector12d& x, double eps_x);

}  // namespace stiffsoft::contact
