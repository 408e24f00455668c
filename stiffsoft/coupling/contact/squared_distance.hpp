#pragma once
/// @file Squared distances of the four IPC primitive pairs (point–point, point–line,
/// point–plane, line–line), with exact gradients and Hessians.
///
/// One formulation serves every pair: d²(x) = min_y ‖r(x, y)‖², where the residual
/// r(x, y) = Σ_i c_i(y) x_i joins the two closest points, its weights c(y) = c₀ + D y are
/// affine in the closest-point parameters y (0, 1 or 2 of them), and r is linear in x for
/// fixed y. With g(x, y) = ‖r‖² and y* the unconstrained minimiser:
///   ∇d²  = g_x = 2 (c(y*) ⊗ r)                     (envelope theorem),
///   ∇²d² = g_xx − g_xy g_yy⁻¹ g_yx                  (implicit function theorem),
/// g_xx = 2 (c cᵀ) ⊗ I₃, g_yy = 2 EᵀE with E = ∂r/∂y (3×M), column k of g_xy = 2 (D_k ⊗ r + c ⊗ E_k).
/// These are the true primitive distances only where the closest points are interior; IPC's
/// classification (distance_classification.hpp) guarantees that where they are used.

#include <Eigen/Core>

#include <stiffsoft/coupling/contact/primitive_pair.hpp>

namespace stiffsoft::contact {

/// The pair's closest points at x: weights c (r = Σ c_i x_i, zero on unused vertices), the
/// residual r from the second primitive's closest point to the first's (metres) and its
/// parameters y (EV: t on the edge; FV: (β₁, β₂) with point f0 + β₁(f1−f0) + β₂(f2−f0);
/// EE: (s, t) along ea and eb; VV: none; unused entries zero).
struct ClosestPoints {
  /// weights of the four stencil vertices in r, dimensionless
  Eigen::Vector4d weights;
  /// residual r = Σ c_i x_i, 3-vector, metres
  Eigen::Vector3d r;
  /// closest-point parameters y*, dimensionless
  Eigen::Vector2d params;
};

/// Closest points of the pair's primitives (points, LINE through the edge, PLANE of the face)
/// at x; see ClosestPoints.
ClosestPoints closest_points(PrimitivePair kind, const Vector12d& x);

/// Squared distance d² of the pair's primitives, m²: VV ‖v0 − v1‖²; EV distance of v to the
/// LINE through e0, e1; FV distance of v to the PLANE of f; EE distance between the two LINES
/// (IPC, Li et al. 2020, §4.3). Degenerate primitives (zero-length edge, parallel edges,
/// collinear face) give the distance to the degenerate set, always finite.
double squared_distance(PrimitivePair kind, const Vector12d& x);

/// ∇_x d², 12-vector, metres; zero on the unused vertices.
Vector12d squared_distance_gradient(PrimitivePair kind, const Vector12d& x);

/// ∇²_x d², 12×12, dimensionless; zero on the unused vertices. Not PSD in general (EE, FV).
Matrix12d squared_distance_hessian(PrimitivePair kind, const Vector12d& x);

/// What ∇²d² is made of at x, from one closest-point solve: with M closest-point parameters
/// (0 VV, 1 EV, 2 FV and EE), B_k = D_k ⊗ r + c ⊗ E_k (k < M) and P = (EᵀE)⁺,
///   ∇²d² = 2 (c cᵀ) ⊗ I₃ − 2 B P Bᵀ,   ∇d² = 2 (c ⊗ r).
/// Both live in span{c ⊗ e_j} + span{d_k ⊗ r}, d_k = D_k less its part along c (at most
/// 3 + M ≤ 5 dimensions): projected_barrier_hessian.hpp works there.
struct DistanceCurvature {
  /// closest-point parameters M (0 VV, 1 EV, 2 FV and EE)
  int M = 0;
  /// weights c(y*) of the four stencil vertices, dimensionless
  Eigen::Vector4d c = Eigen::Vector4d::Zero();
  /// residual r between the closest points, metres
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  /// ∂c/∂y, first M columns used, dimensionless
  Eigen::Matrix<double, 4, 2> D = Eigen::Matrix<double, 4, 2>::Zero();
  /// ∂r/∂y, first M columns used, metres
  Eigen::Matrix<double, 3, 2> E = Eigen::Matrix<double, 3, 2>::Zero();
  /// (EᵀE)⁺, leading M×M used, m⁻²
  Eigen::Matrix2d gram_pinv = Eigen::Matrix2d::Zero();
};

/// The factors of ∇²d² of the pair at x (see DistanceCurvature).
DistanceCurvature distance_curvature(PrimitivePair kind, const Vector12d& x);

}  // namespace stiffsoft::contact
