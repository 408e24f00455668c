#include <stiffsoft/coupling/contact/squared_distance.hpp>

#include <cmath>

namespace stiffsoft::contact {

namespace {

/// Affine weights c(y) = c₀ + D y of the residual r(x, y) = Σ_i c_i(y) x_i, M parameters.
template <int M>
struct AffineResidual {
  Eigen::Vector4d c0;
  Eigen::Matrix<double, 4, M> D;
};

/// EV: r = v − (e0 + t (e1 − e0)).
AffineResidual<1> edge_vertex_residual() {
  return {Eigen::Vector4d(1, -1, 0, 0), Eigen::Vector4d(0, 1, -1, 0)};
}

/// FV: r = v − (f0 + β₁ (f1 − f0) + β₂ (f2 − f0)).
AffineResidual<2> face_vertex_residual() {
  Eigen::Matrix<double, 4, 2> D;
  D << 0, 0, 1, 1, -1, 0, 0, -1;
  return {Eigen::Vector4d(1, -1, 0, 0), D};
}

/// EE: r = (ea0 + s (ea1 − ea0)) − (eb0 + t (eb1 − eb0)).
AffineResidual<2> edge_edge_residual() {
  Eigen::Matrix<double, 4, 2> D;
  D << -1, 0, 1, 0, 0, 1, 0, -1;
  return {Eigen::Vector4d(1, 0, -1, 0), D};
}

/// Σ_i w_i x_i for a packed stencil (inlined: the closest points of every pair call it M + 1 times).
[[gnu::always_inline]] inline Eigen::Vector3d combine(const Vector12d& x, const Eigen::Vector4d& w) {
  return w[0] * x.segment<3>(0) + w[1] * x.segment<3>(3) + w[2] * x.segment<3>(6) +
         w[3] * x.segment<3>(9);
}

/// Moore–Penrose inverse of the 1×1 Gram matrix; 0 for a degenerate (zero-length) edge,
/// which makes the point–line distance fall back to the point–point one (finite, not NaN).
Eigen::Matrix<double, 1, 1> gram_pinv(const Eigen::Matrix<double, 1, 1>& A) {
  Eigen::Matrix<double, 1, 1> inv;
  inv(0, 0) = A(0, 0) > 0.0 ? 1.0 / A(0, 0) : 0.0;
  return inv;
}

/// Inverse of the symmetric PSD 2×2 Gram matrix EᵀE; for (numerically) parallel edges or a
/// degenerate triangle it falls back to the pseudo-inverse so values stay finite: the
/// minimiser is then not unique, but the minimum ‖r‖² is.
Eigen::Matrix2d gram_pinv(const Eigen::Matrix2d& A) {
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
Vector12d kron_gradient(const Eigen::Vector4d& c, const Eigen::Vector3d& r) {
  Vector12d g;
  for (int i = 0; i < 4; ++i) g.segment<3>(3 * i) = 2.0 * c[i] * r;
  return g;
}

/// 2 (c cᵀ) ⊗ I₃.
Matrix12d kron_identity(const Eigen::Vector4d& c) {
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

/// The factors of ∇²d² from the minimiser of an M-parameter residual.
template <int M>
DistanceCurvature residual_curvature(const AffineResidual<M>& res, const Vector12d& x) {
  const ResidualMinimum<M> m = minimize_residual(res, x);
  DistanceCurvature k;
  k.M = M;
  k.c = m.c;
  k.r = m.r;
  k.D.leftCols<M>() = res.D;
  k.E.leftCols<M>() = m.E;
  k.gram_pinv.topLeftCorner<M, M>() = m.gram_pinv;
  return k;
}

}  // namespace

DistanceCurvature distance_curvature(PrimitivePair kind, const Vector12d& x) {
  switch (kind) {
    case PrimitivePair::VertexVertex: {
      DistanceCurvature k;
      k.c = Eigen::Vector4d(1, -1, 0, 0);
      k.r = combine(x, k.c);
      return k;
    }
    case PrimitivePair::EdgeVertex: return residual_curvature(edge_vertex_residual(), x);
    case PrimitivePair::EdgeEdge: return residual_curvature(edge_edge_residual(), x);
    case PrimitivePair::FaceVertex: return residual_curvature(face_vertex_residual(), x);
  }
  return {};
}

ClosestPoints closest_points(PrimitivePair kind, const Vector12d& x) {
  ClosestPoints cp;
  cp.params.setZero();
  // The minimiser's weights, residual and its M parameters (the rest stay zero).
  const auto take = [&cp](const auto& m) {
    cp.weights = m.c;
    cp.r = m.r;
    cp.params.head(m.y.size()) = m.y;
  };
  switch (kind) {
    case PrimitivePair::VertexVertex:
      cp.weights = Eigen::Vector4d(1, -1, 0, 0);
      cp.r = combine(x, cp.weights);
      break;
    case PrimitivePair::EdgeVertex: take(minimize_residual(edge_vertex_residual(), x)); break;
    case PrimitivePair::EdgeEdge: take(minimize_residual(edge_edge_residual(), x)); break;
    case PrimitivePair::FaceVertex: take(minimize_residual(face_vertex_residual(), x)); break;
  }
  return cp;
}

double squared_distance(PrimitivePair kind, const Vector12d& x) {
  return closest_points(kind, x).r.squaredNorm();
}

Vector12d squared_distance_gradient(PrimitivePair kind, const Vector12d& x) {
  const ClosestPoints cp = closest_points(kind, x);
  return kron_gradient(cp.weights, cp.r);
}

Matrix12d squared_distance_hessian(PrimitivePair kind, const Vector12d& x) {
  switch (kind) {
    case PrimitivePair::VertexVertex: return kron_identity(Eigen::Vector4d(1, -1, 0, 0));
    case PrimitivePair::EdgeVertex: return residual_hessian(edge_vertex_residual(), x);
    case PrimitivePair::EdgeEdge: return residual_hessian(edge_edge_residual(), x);
    case PrimitivePair::FaceVertex: return residual_hessian(face_vertex_residual(), x);
  }
  return Matrix12d::Zero();
}

}  // namespace stiffsoft::contact
