#include <stiffsoft/coupling/contact/friction.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace stiffsoft::contact {

Eigen::Matrix<double, 3, 2> orthonormal_complement(const Eigen::Vector3d& n) {
  // Cross with the axis least aligned with n keeps the first tangent well conditioned.
  Eigen::Index axis;
  n.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d t0 = n.cross(Eigen::Vector3d::Unit(axis)).normalized();
  Eigen::Matrix<double, 3, 2> P;
  P.col(0) = t0;
  P.col(1) = n.cross(t0);
  return P;
}

FrictionStencil make_friction_stencil(const Stencil& s, const Vector12d& x_lag, double dhat,
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
  f.T = f.P.transpose() * f.Gamma;
  return f;
}

double friction_f0(double y, double eps) {
  if (y >= eps) return y;
  return -y * y * y / (3.0 * eps * eps) + y * y / eps + eps / 3.0;
}

double friction_f1(double y, double eps) {
  if (y >= eps) return 1.0;
  return 2.0 * y / eps - y * y / (eps * eps);
}

double friction_f1_over_y(double y, double eps) {
  if (y >= eps) return 1.0 / y;
  return 2.0 / eps - y / (eps * eps);
}

double friction_potential(const FrictionStencil& f, const Vector12d& dx, double mu, double epsv_h) {
  if (mu == 0.0 || f.normal_force == 0.0) return 0.0;
  const Eigen::Vector2d u = tangent_operator(f) * dx;
  return mu * f.normal_force * friction_f0(u.norm(), epsv_h);
}

Vector12d friction_potential_gradient(const FrictionStencil& f, const Vector12d& dx, double mu,
                                      double epsv_h) {
  if (mu == 0.0 || f.normal_force == 0.0) return Vector12d::Zero();
  const Eigen::Matrix<double, 2, 12> T = tangent_operator(f);
  const Eigen::Vector2d u = T * dx;
  return mu * f.normal_force * friction_f1_over_y(u.norm(), epsv_h) * (T.transpose() * u);
}

FrictionHessianFactors friction_hessian_factors(const FrictionStencil& f, const Vector12d& dx, double mu,
                                                double epsv_h, bool project_psd) {
  FrictionHessianFactors out{tangent_operator(f), Eigen::Matrix2d::Zero()};
  if (mu == 0.0 || f.normal_force == 0.0) return out;
  const Eigen::Vector2d u = out.T * dx;
  const double y = u.norm();
  // M = a I − w û ûᵀ: eigenvalue a > 0 across the slide and a − w along it, which is 0 when
  // sliding (y ≥ ε) and 2 (ε − y) / ε² > 0 inside the stick zone, so the projection clamps a − w
  // only where rounding took it below zero: no eigen-decomposition.
  const double a = friction_f1_over_y(y, epsv_h);
  Eigen::Matrix2d M = a * Eigen::Matrix2d::Identity();
  if (y > 0.0) {
    const Eigen::Vector2d uh = u / y;
    const double w = y >= epsv_h ? 1.0 / y : y / (epsv_h * epsv_h);
    M -= (project_psd ? std::min(w, a) : w) * uh * uh.transpose();
  }
  out.C = (mu * f.normal_force) * M;
  return out;
}

Matrix12d friction_potential_hessian(const FrictionStencil& f, const Vector12d& dx, double mu,
                                     double epsv_h, bool project_psd) {
  if (mu == 0.0 || f.normal_force == 0.0) return Matrix12d::Zero();
  const FrictionHessianFactors h = friction_hessian_factors(f, dx, mu, epsv_h, project_psd);
  // Coefficient-based product: Eigen would send a 12×2×12 product to its blocked GEMM.
  return h.T.transpose().lazyProduct(h.C * h.T);
}

FrictionHessianFactors friction_majorizer_factors(const FrictionStencil& f, const Vector12d& dx, double mu,
                                                  double epsv_h) {
  FrictionHessianFactors out{tangent_operator(f), Eigen::Matrix2d::Zero()};
  if (mu == 0.0 || f.normal_force == 0.0) return out;
  const double y = (out.T * dx).norm();
  out.C = (mu * f.normal_force * friction_f1_over_y(y, epsv_h)) * Eigen::Matrix2d::Identity();
  return out;
}

Matrix12d friction_majorizer_hessian(const FrictionStencil& f, const Vector12d& dx, double mu,
                                     double epsv_h) {
  if (mu == 0.0 || f.normal_force == 0.0) return Matrix12d::Zero();
  const FrictionHessianFactors h = friction_majorizer_factors(f, dx, mu, epsv_h);
  return h.C(0, 0) * h.T.transpose() * h.T;
}

bool step_reverses_slide(const FrictionStencil& f, const Vector12d& dx, const Vector12d& dx_step,
                         double epsv_h) {
  const Eigen::Matrix<double, 2, 12> T = tangent_operator(f);
  const Eigen::Vector2d u = T * dx;
  return u.norm() >= epsv_h && u.dot(u + T * dx_step) < 0;
}
}  // namespace stiffsoft::contact
