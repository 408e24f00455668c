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
#include <cmath>

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

namespace detail {

/// Affine weights c(y) = c₀ + D y of the residual r(x, y) = Σ_i c_i(y) x_i, M parameters.
template <int M>
struct AffineResidual {
  Eigen::Vector4d c0;
  Eigen::Matrix<double, 4, M> D;
};

/// EV: r = v − (e0 + t (e1 − e0)).
inline AffineResidual<1> edge_vertex_residual() {
  return {Eigen::Vector4d(1, -1, 0, 0), Eigen::Vector4d(0, 1, -1, 0)};
}

/// FV: r = v − (f0 + β₁ (f1 − f0) + β₂ (f2 − f0)).
inline AffineResidual<2> face_vertex_residual() {
  Eigen::Matrix<double, 4, 2> D;
  D << 0, 0, 1, 1, -1, 0, 0, -1;
  return {Eigen::Vector4d(1, -1, 0, 0), D};
}

/// EE: r = (ea0 + s (ea1 − ea0)) − (eb0 + t (eb1 − eb0)).
inline AffineResidual<2> edge_edge_residual() {
  Eigen::Matrix<double, 4, 2> D;
  D << -1, 0, 1, 0, 0, 1, 0, -1;
  return {Eigen::Vector4d(1, 0, -1, 0), D};
}

/// Σ_i w_i x_i for a packed stencil.
inline Eigen::Vector3d combine(const Vector12d& x, const Eigen::Vector4d& w) {
  return w[0] * x.segment<3>(0) + w[1] * x.segment<3>(3) + w[2] * x.segment<3>(6) +
         w[3] * x.segment<3>(9);
}

/// Moore–Penrose inverse of the 1×1 Gram matrix; 0 for a degenerate (zero-length) edge,
/// which makes the point–line distance fall back to the point–point one (finite, not NaN).
inline Eigen::Matrix<double, 1, 1> gram_pinv(const Eigen::Matrix<double, 1, 1>& A) {
  Eigen::Matrix<double, 1, 1> inv;
  inv(0, 0) = A(0, 0) > 0.0 ? 1.0 / A(0, 0) : 0.0;
  return inv;
}

/// Inverse of the symmetric PSD 2×2 Gram matrix EᵀE; for (numerically) parallel edges or a
/// degenerate triangle it falls back to the pseudo-inverse so values stay finite: the
/// minimiser is then not unique, but the minimum ‖r‖² is.
inline Eigen::Matrix2d gram_pinv(const Eigen::Matrix2d& A) {
  const double det = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0);
  // 1e-14·A00·A11 = sin²θ between the two directions; below it the explicit inverse loses
  // every digit, so treat the pair as rank one.
  if (det > 1e-14 * A(0, 0) * A(1, 1)) {
    Eigen::Matrix2d inv;
    inv << A(1, 1), -A(0, 1), -A(1, 0), A(0, 0);
    return inv / det;
  }
  const double trace = A(0, 0) + A(1, 1);
  if (!(trace > 0.0)) return Eigen::Matrix2d::Zero();
  // Rank one: A ≈ trace · v vᵀ with v the dominant direction.
  const Eigen::Vector2d v = A(0, 0) >= A(1, 1) ? Eigen::Vector2d(A(0, 0), A(1, 0))
                                               : Eigen::Vector2d(A(0, 1), A(1, 1));
  const Eigen::Vector2d u = v.normalized();
  return u * u.transpose() / trace;
}

/// The minimiser y* of ‖r(x, y)‖² and the quantities its derivatives need.
template <int M>
struct ResidualMinimum {
  Eigen::Vector4d c;                      ///< c(y*)
  Eigen::Vector3d r;                      ///< r(x, y*)
  Eigen::Matrix<double, 3, M> E;          ///< ∂r/∂y
  Eigen::Matrix<double, M, M> gram_pinv;  ///< (EᵀE)⁺
  Eigen::Matrix<double, M, 1> y;          ///< y*
};

/// Solves min_y ‖r(x, y)‖² through the normal equations (EᵀE) y = −Eᵀ r₀.
template <int M>
ResidualMinimum<M> minimize_residual(const AffineResidual<M>& res, const Vector12d& x) {
  ResidualMinimum<M> out;
  for (int k = 0; k < M; ++k) out.E.col(k) = combine(x, res.D.col(k));
  const Eigen::Vector3d r0 = combine(x, res.c0);
  out.gram_pinv = gram_pinv(Eigen::Matrix<double, M, M>(out.E.transpose() * out.E));
  // Normal equations EᵀE y = −Eᵀ r₀ of the linear least-squares problem in y.
  out.y = -out.gram_pinv * (out.E.transpose() * r0);
  out.c = res.c0 + res.D * out.y;
  out.r = r0 + out.E * out.y;
  return out;
}

/// 2 (c ⊗ r), the envelope-theorem gradient.
inline Vector12d kron_gradient(const Eigen::Vector4d& c, const Eigen::Vector3d& r) {
  Vector12d g;
  for (int i = 0; i < 4; ++i) g.segment<3>(3 * i) = 2.0 * c[i] * r;
  return g;
}

/// 2 (c cᵀ) ⊗ I₃.
inline Matrix12d kron_identity(const Eigen::Vector4d& c) {
  Matrix12d H = Matrix12d::Zero();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) H.block<3, 3>(3 * i, 3 * j).diagonal().setConstant(2.0 * c[i] * c[j]);
  return H;
}

/// ∇²d² = g_xx − g_xy g_yy⁻¹ g_yx at the minimiser (implicit function theorem).
template <int M>
Matrix12d residual_hessian(const AffineResidual<M>& res, const Vector12d& x) {
  const ResidualMinimum<M> m = minimize_residual(res, x);
  // B = ½ g_xy: column k is D_k ⊗ r + c ⊗ E_k.
  Eigen::Matrix<double, 12, M> B;
  for (int k = 0; k < M; ++k)
    for (int i = 0; i < 4; ++i)
      B.col(k).template segment<3>(3 * i) = res.D(i, k) * m.r + m.c[i] * m.E.col(k);
  // g_xy g_yy⁻¹ g_yx = (2B)(2EᵀE)⁻¹(2B)ᵀ = 2 B (EᵀE)⁻¹ Bᵀ.
  return kron_identity(m.c) - 2.0 * B * m.gram_pinv * B.transpose();
}

}  // namespace detail

/// Closest points of the pair's primitives (points, LINE through the edge, PLANE of the face)
/// at x; see ClosestPoints.
inline ClosestPoints closest_points(PrimitivePair kind, const Vector12d& x) {
  ClosestPoints cp;
  cp.params.setZero();
  switch (kind) {
    case PrimitivePair::VertexVertex:
      cp.weights = Eigen::Vector4d(1, -1, 0, 0);
      cp.r = detail::combine(x, cp.weights);
      break;
    case PrimitivePair::EdgeVertex: {
      const auto m = detail::minimize_residual(detail::edge_vertex_residual(), x);
      cp.weights = m.c;
      cp.r = m.r;
      cp.params[0] = m.y[0];
      break;
    }
    case PrimitivePair::EdgeEdge: {
      const auto m = detail::minimize_residual(detail::edge_edge_residual(), x);
      cp.weights = m.c;
      cp.r = m.r;
      cp.params = m.y;
      break;
    }
    case PrimitivePair::FaceVertex: {
      const auto m = detail::minimize_residual(detail::face_vertex_residual(), x);
      cp.weights = m.c;
      cp.r = m.r;
      cp.params = m.y;
      break;
    }
  }
  return cp;
}

/// Squared distance d² of the pair's primitives, m²: VV ‖v0 − v1‖²; EV distance of v to the
/// LINE through e0, e1; FV distance of v to the PLANE of f; EE distance between the two LINES
/// (IPC, Li et al. 2020, §4.3). Degenerate primitives (zero-length edge, parallel edges,
/// collinear face) give the distance to the degenerate set, always finite.
inline double squared_distance(PrimitivePair kind, const Vector12d& x) {
  return closest_points(kind, x).r.squaredNorm();
}

/// ∇_x d², 12-vector, metres; zero on the unused vertices.
inline Vector12d squared_distance_gradient(PrimitivePair kind, const Vector12d& x) {
  const ClosestPoints cp = closest_points(kind, x);
  return detail::kron_gradient(cp.weights, cp.r);
}

/// ∇²_x d², 12×12, dimensionless; zero on the unused vertices. Not PSD in general (EE, FV).
inline Matrix12d squared_distance_hessian(PrimitivePair kind, const Vector12d& x) {
  switch (kind) {
    case PrimitivePair::VertexVertex: return detail::kron_identity(Eigen::Vector4d(1, -1, 0, 0));
    case PrimitivePair::EdgeVertex: return detail::residual_hessian(detail::edge_vertex_residual(), x);
    case PrimitivePair::EdgeEdge: return detail::residual_hessian(detail::edge_edge_residual(), x);
    case PrimitivePair::FaceVertex: return detail::residual_hessian(detail::face_vertex_residual(), x);
  }
  return Matrix12d::Zero();
}

}  // namespace stiffsoft::contact
