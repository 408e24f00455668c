#pragma once
/// @file Lagged, smoothed friction of one contact stencil (IPC, Li et al. 2020, §5, eqs. 14–18).
/// D(dx) = μ λ f₀(‖u‖), u = Pᵀ Γ dx: λ (normal force), P (tangent basis) and Γ (closest-point
/// operator) are frozen at the lagged configuration; dx = x − xⁿ is the step's displacement.

#include <Eigen/Core>
#include <cmath>
#include <limits>

#include <stiffsoft/coupling/contact/barrier.hpp>
#include <stiffsoft/coupling/contact/barrier_potential.hpp>
#include <stiffsoft/coupling/contact/primitive_pair.hpp>
#include <stiffsoft/coupling/contact/psd_projection.hpp>

namespace stiffsoft::contact {

/// Friction data of one stencil, built once per lag by make_friction_stencil.
struct FrictionStencil {
  /// primitive pair of the stencil it was built from
  PrimitivePair kind = PrimitivePair::VertexVertex;
  /// lagged normal force magnitude λ ≥ 0, N
  double normal_force = 0;
  /// orthonormal tangent basis, 3×2, of the plane orthogonal to the contact normal
  Eigen::Matrix<double, 3, 2> P = Eigen::Matrix<double, 3, 2>::Zero();
  /// relative closest-point displacement operator, 3×12: u₃ = Γ dx = Σ c_i dx_i
  Eigen::Matrix<double, 3, 12> Gamma = Eigen::Matrix<double, 3, 12>::Zero();
};

/// Tangential operator T = Pᵀ Γ, 2×12: u = T dx.
inline Eigen::Matrix<double, 2, 12> tangent_operator(const FrictionStencil& f) { return f.P.transpose() * f.Gamma; }

/// An orthonormal basis (3×2) of the plane orthogonal to the unit vector n.
inline Eigen::Matrix<double, 3, 2> orthonormal_complement(const Eigen::Vector3d& n) {
  // Cross with the axis least aligned with n keeps the first tangent well conditioned.
  Eigen::Index axis;
  n.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d t0 = n.cross(Eigen::Vector3d::Unit(axis)).normalized();
  Eigen::Matrix<double, 3, 2> P;
  P.col(0) = t0;
  P.col(1) = n.cross(t0);
  return P;
}

/// Builds the lagged friction data from x_lag (IPC §5):
/// λ = κ m(x_lag) (−b'(d²)) 2d — the normal force κ |∂(m b)/∂d| with the mollifier value m
/// kept as a factor (m ≡ 1 unless the stencil is mollified), 0 when d ≥ d̂, +∞ when d = 0;
/// Γ = c(y*) ⊗ I₃ from the stencil's closest points (classified for segment-distance stencils);
/// P spans the plane orthogonal to the normal n = r/‖r‖ (r joins the closest points; for a
/// touching stencil, d = 0, the face normal or ea × eb is used, else an arbitrary axis).
/// Friction is isotropic, so any orthonormal P of that plane gives the same D.
/// dhat: d̂, m; kappa: barrier stiffness κ, N/m³.
inline FrictionStencil make_friction_stencil(const Stencil& s, const Vector12d& x_lag, double dhat,
                                             double kappa) {
  FrictionStencil f;
  f.kind = s.kind;
  const ClosestPoints cp = stencil_closest_points(s, x_lag);
  const double d2 = cp.r.squaredNorm();
  if (d2 <= 0.0) {
    // Touching (d = 0) never happens inside IPC's feasible set; the force is infinite there,
    // and saying so beats the NaN of 0·∞.
    f.normal_force = std::numeric_limits<double>::infinity();
  } else if (d2 < dhat * dhat) {
    const double m = is_mollified(s) ? edge_edge_mollifier(x_lag, s.eps_x) : 1.0;
    f.normal_force = kappa * m * (-barrier_first_derivative(d2, dhat)) * 2.0 * std::sqrt(d2);
  }
  for (int i = 0; i < 4; ++i) f.Gamma.block<3, 3>(0, 3 * i) = cp.weights[i] * Eigen::Matrix3d::Identity();

  Eigen::Vector3d n = cp.r;
  if (!(n.squaredNorm() > 0.0)) {
    const Eigen::Vector3d x0 = x_lag.segment<3>(0), x1 = x_lag.segment<3>(3), x2 = x_lag.segment<3>(6),
                          x3 = x_lag.segment<3>(9);
    if (s.kind == PrimitivePair::FaceVertex) n = (x2 - x1).cross(x3 - x1);
    if (s.kind == PrimitivePair::EdgeEdge) n = (x1 - x0).cross(x3 - x2);
    if (!(n.squaredNorm() > 0.0)) n = Eigen::Vector3d::UnitZ();
  }
  f.P = orthonormal_complement(n.normalized());
  return f;
}

/// Smoothed friction magnitude f₀(y) = −y³/(3ε²) + y²/ε + ε/3 for y < ε, y otherwise
/// (IPC eq. 15 integrated; C² at ε). y = ‖u‖, m; eps = ε_v h, m.
inline double friction_f0(double y, double eps) {
  if (y >= eps) return y;
  return -y * y * y / (3.0 * eps * eps) + y * y / eps + eps / 3.0;
}

/// f₁(y) = f₀'(y) = 2y/ε − y²/ε² for y < ε, 1 otherwise; dimensionless.
inline double friction_f1(double y, double eps) {
  if (y >= eps) return 1.0;
  return 2.0 * y / eps - y * y / (eps * eps);
}

/// f₁(y)/y = 2/ε − y/ε² for y < ε, 1/y otherwise (finite at y = 0), 1/m.
inline double friction_f1_over_y(double y, double eps) {
  if (y >= eps) return 1.0 / y;
  return 2.0 / eps - y / (eps * eps);
}

/// Friction potential D = μ λ f₀(‖u‖), u = Pᵀ Γ dx; J. dx: step displacement of the stencil,
/// 12-vector, m; mu: friction coefficient; epsv_h: ε = ε_v h, m.
inline double friction_potential(const FrictionStencil& f, const Vector12d& dx, double mu, double epsv_h) {
  if (mu == 0.0 || f.normal_force == 0.0) return 0.0;
  const Eigen::Vector2d u = tangent_operator(f) * dx;
  return mu * f.normal_force * friction_f0(u.norm(), epsv_h);
}

/// ∇D = μ λ (f₁(y)/y) Tᵀ u, T = PᵀΓ; 12-vector, N. Its magnitude is μλ‖Tᵀû‖ when sliding.
inline Vector12d friction_potential_gradient(const FrictionStencil& f, const Vector12d& dx, double mu,
                                             double epsv_h) {
  if (mu == 0.0 || f.normal_force == 0.0) return Vector12d::Zero();
  const Eigen::Matrix<double, 2, 12> T = tangent_operator(f);
  const Eigen::Vector2d u = T * dx;
  return mu * f.normal_force * friction_f1_over_y(u.norm(), epsv_h) * (T.transpose() * u);
}

/// ∇²D = μ λ Tᵀ M T with the 2×2 core (y = ‖u‖, û = u/y)
///   y ≥ ε:     M = (I − û ûᵀ)/y,
///   0 < y < ε: M = (f₁/y) I + (f₁' y − f₁)/y³ u uᵀ = (2/ε − y/ε²) I − (y/ε²) û ûᵀ,
///   y = 0:     M = (2/ε) I;
/// N/m. project_psd projects the 2×2 core (as ipc-toolkit does), which keeps Tᵀ M T PSD;
/// the exact core above is PSD already for y ≤ ε, so the projection only guards round-off.
inline Matrix12d friction_potential_hessian(const FrictionStencil& f, const Vector12d& dx, double mu,
                                            double epsv_h, bool project_psd) {
  if (mu == 0.0 || f.normal_force == 0.0) return Matrix12d::Zero();
  const Eigen::Matrix<double, 2, 12> T = tangent_operator(f);
  const Eigen::Vector2d u = T * dx;
  const double y = u.norm();
  Eigen::Matrix2d M = friction_f1_over_y(y, epsv_h) * Eigen::Matrix2d::Identity();
  if (y > 0.0) {
    const Eigen::Vector2d uh = u / y;
    const double w = y >= epsv_h ? 1.0 / y : y / (epsv_h * epsv_h);
    M -= w * uh * uh.transpose();
  }
  if (project_psd) M = project_to_psd<2>(M);
  // Coefficient-based product: Eigen would send a 12×2×12 product to its blocked GEMM.
  return (mu * f.normal_force) * T.transpose().lazyProduct(M * T);
}

/// The isotropic majorizer of D's Hessian: μ λ Tᵀ (f₁(y)/y) I T, N/m. Its quadratic model lies
/// above D in every direction (f₀(‖v‖) is concave in ‖v‖², so the quadratic in v that touches
/// it at u with slope f₁(y)/y bounds it from above), and it exceeds the exact Hessian by
/// μ λ Tᵀ (f₁/y − f₁') û ûᵀ T ⪰ 0. Where the exact Hessian has no curvature along the slide
/// (y ≥ ε), a Newton step sized by the other terms can run u through the stick zone and out the
/// other side, where D has risen linearly; a step on this model stops short of reversing it.
inline Matrix12d friction_majorizer_hessian(const FrictionStencil& f, const Vector12d& dx, double mu,
                                            double epsv_h) {
  if (mu == 0.0 || f.normal_force == 0.0) return Matrix12d::Zero();
  const Eigen::Matrix<double, 2, 12> T = tangent_operator(f);
  const double y = (T * dx).norm();
  return mu * f.normal_force * friction_f1_over_y(y, epsv_h) * T.transpose() * T;
}

/// Whether the step dx_step reverses the slide of a stencil displaced by dx: it slides
/// (‖u‖ ≥ ε) and the full step ends on the far side, u·(u + T dx_step) < 0.
inline bool step_reverses_slide(const FrictionStencil& f, const Vector12d& dx, const Vector12d& dx_step,
                                double epsv_h) {
  const Eigen::Matrix<double, 2, 12> T = tangent_operator(f);
  const Eigen::Vector2d u = T * dx;
  return u.norm() >= epsv_h && u.dot(u + T * dx_step) < 0;
}

}  // namespace stiffsoft::contact
