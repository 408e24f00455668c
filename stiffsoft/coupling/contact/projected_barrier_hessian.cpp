#include <stiffsoft/coupling/contact/projected_barrier_hessian.hpp>
#include <stiffsoft/coupling/contact/symmetric_eigen.hpp>

#include <cmath>

namespace stiffsoft::contact {

namespace {

/// The projection for M closest-point parameters (the order of S is 3 + M).
template <int M>
LowRankHessian project_in_distance_span(const DistanceCurvature& k, double db, double ddb) {
  constexpr int n = 3 + M;
  const double c2 = k.c.squaredNorm(), c_norm = std::sqrt(c2), r_norm = k.r.norm();
  const Eigen::Vector4d c_hat = k.c / c_norm;
  const Eigen::Vector3d r_hat = r_norm > 0.0 ? Eigen::Vector3d(k.r / r_norm) : Eigen::Vector3d::Zero();
  // q_l: Gram–Schmidt over the D_k less their parts along c (never parallel to c: c's first
  // vertex weight is 1 where every D_k has 0, or its first two weights sum to 1 where D_k's sum to 0).
  Eigen::Matrix<double, 4, 2> q = Eigen::Matrix<double, 4, 2>::Zero();  // first M columns used
  for (int l = 0; l < M; ++l) {
    Eigen::Vector4d v = k.D.col(l) - c_hat.dot(k.D.col(l)) * c_hat;
    for (int j = 0; j < l; ++j) v -= q.col(j).dot(v) * q.col(j);
    const double v_norm = v.norm();
    q.col(l) = v_norm > 0.0 ? Eigen::Vector4d(v / v_norm) : Eigen::Vector4d::Zero();
  }
  // S: the Hessian in the basis [ĉ ⊗ e_1, ĉ ⊗ e_2, ĉ ⊗ e_3, q_l ⊗ r̂].
  Eigen::Matrix<double, n, n> S = Eigen::Matrix<double, n, n>::Zero();
  S.template topLeftCorner<3, 3>() = c2 * (4.0 * ddb * k.r * k.r.transpose());
  S.template topLeftCorner<3, 3>().diagonal().array() += 2.0 * db * c2;
  if constexpr (M > 0) {
    Eigen::Matrix<double, n, M> Y;  // coordinates of B_k
    for (int j = 0; j < M; ++j) {
      Y.col(j).template head<3>() = (k.c.dot(k.D.col(j)) * k.r + c2 * k.E.col(j)) / c_norm;
      for (int l = 0; l < M; ++l) Y(3 + l, j) = r_norm * q.col(l).dot(k.D.col(j));
    }
    S.noalias() -= (2.0 * db) * Y.lazyProduct(k.gram_pinv.template topLeftCorner<M, M>()).lazyProduct(Y.transpose());
  }
  const SymmetricEigen<n> es = checked_symmetric_eigen<n>(S);
  // H₊ = Σ_m λ_m⁺ g_m g_mᵀ, g_m = ĉ ⊗ v_m,head + (q v_m,tail) ⊗ r̂.
  LowRankHessian H;
  for (int m = 0; m < n; ++m) {
    const double lambda = es.values[m];
    if (!(lambda > 0.0)) continue;
    const auto v = es.vectors.col(m);
    Eigen::Vector4d along_r = Eigen::Vector4d::Zero();
    if constexpr (M > 0) along_r = q.leftCols<M>() * v.template tail<M>();
    for (int i = 0; i < 4; ++i) H.G.row(H.rank).segment<3>(3 * i) = c_hat[i] * v.template head<3>() + along_r[i] * r_hat;
    H.lambda[H.rank++] = lambda;
  }
  return H;
}

}  // namespace

Matrix12d LowRankHessian::formed() const {
  Matrix12d H = Matrix12d::Zero();
  for (int m = 0; m < rank; ++m) H.selfadjointView<Eigen::Lower>().rankUpdate(Vector12d(G.row(m).transpose()), lambda[m]);
  return H.selfadjointView<Eigen::Lower>();
}

LowRankHessian projected_barrier_factors(const DistanceCurvature& k, double db, double ddb) {
  switch (k.M) {
    case 0: return project_in_distance_span<0>(k, db, ddb);
    case 1: return project_in_distance_span<1>(k, db, ddb);
    default: return project_in_distance_span<2>(k, db, ddb);
  }
}

Matrix12d projected_barrier_hessian(const DistanceCurvature& k, double db, double ddb) {
  return projected_barrier_factors(k, db, ddb).formed();
}

LowRankHessian projected_barrier_factors(const Stencil& s, const Vector12d& x, double dhat) {
  const auto project = [dhat](PrimitivePair kind, const Vector12d& y) -> LowRankHessian {
    const DistanceCurvature k = distance_curvature(kind, y);
    const double d2 = k.r.squaredNorm();
    if (d2 >= dhat * dhat) return {};
    return projected_barrier_factors(k, barrier_first_derivative(d2, dhat), barrier_second_derivative(d2, dhat));
  };
  if (!uses_segment_distance(s)) return project(s.kind, x);
  const Classified c = classify_edge_edge_stencil(x);
  LowRankHessian H = project(c.kind, gather_classified(c, x));
  for (int m = 0; m < H.rank; ++m) H.G.row(m) = scatter_classified(c, Vector12d(H.G.row(m).transpose())).transpose();
  return H;
}

Matrix12d projected_barrier_hessian(const Stencil& s, const Vector12d& x, double dhat) {
  return projected_barrier_factors(s, x, dhat).formed();
}

}  // namespace stiffsoft::contact
