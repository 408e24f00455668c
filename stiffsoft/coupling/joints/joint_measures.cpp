#include <stiffsoft/coupling/joints/joint_measures.hpp>

#include <Eigen/Geometry>
#include <cmath>

#include <stiffsoft/coupling/joints/dual2.hpp>

namespace stiffsoft {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Matrix3d cross_matrix(const Vector3d& v) {
  Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// Pulls derivatives in (r, u), r = x_a − x_b, back to y = [x_a; x_b; u].
void from_r_u(const Vector3d& g_r, const Vector3d& g_u, const Matrix3d& H_rr, const Matrix3d& H_ru,
              const Matrix3d& H_uu, MeasureValue& out) {
  out.grad.resize(9);
  out.grad << g_r, -g_r, g_u;
  out.hess.resize(9, 9);
  out.hess << H_rr, -H_rr, H_ru,  //
      -H_rr, H_rr, -H_ru,         //
      H_ru.transpose(), -H_ru.transpose(), H_uu;
}

/// The bend angle atan2(|e_a × e_b|, e_a·e_b) over Dual2 (y = [e_a; e_b]).
Dual2<6> bend_dual(const Eigen::VectorXd& y) {
  using V = Dual2Vector3<6>;
  const V a = V::variables(0, y.segment<3>(0)), b = V::variables(1, y.segment<3>(3));
  const V w = cross(a, b);
  return atan2(sqrt(dot(w, w)), dot(a, b));
}

/// twist_angle() over Dual2 (y = [e_a; e_b; r_a; r_b]).
Dual2<12> twist_dual(const Eigen::VectorXd& y) {
  using D = Dual2<12>;
  using V = Dual2Vector3<12>;
  const V ea = normalized(V::variables(0, y.segment<3>(0))), eb = normalized(V::variables(1, y.segment<3>(3)));
  const V ra = V::variables(2, y.segment<3>(6)), rb = V::variables(3, y.segment<3>(9));
  const V w = cross(ea, eb);
  const D c = dot(ea, eb);
  const V v = c * ra + cross(w, ra) + (dot(w, ra) / (D::constant(1) + c)) * w;  // S r_a
  return atan2(dot(eb, cross(rb, v)), dot(rb, v));
}

template <int N>
void from_dual(const Dual2<N>& d, MeasureValue& out) {
  out.s = d.v;
  out.grad = d.g;
  out.hess = d.H;
}

}  // namespace

int measure_vectors(JointMeasure measure) {
  switch (measure) {
    case JointMeasure::Distance:
    case JointMeasure::BendAngle: return 2;
    case JointMeasure::TwistAngle: return 4;
    default: return 3;
  }
}

bool measure_is_angle(JointMeasure measure) {
  return measure == JointMeasure::HingeAngle || measure == JointMeasure::BendAngle ||
         measure == JointMeasure::TwistAngle;
}

double twist_angle(const Vector3d& e_a, const Vector3d& e_b, const Vector3d& r_a, const Vector3d& r_b) {
  const Vector3d ea = e_a.normalized(), eb = e_b.normalized();
  const Vector3d w = ea.cross(eb);
  const double c = ea.dot(eb);
  const Vector3d v = c * r_a + w.cross(r_a) + (w.dot(r_a) / (1 + c)) * w;
  return std::atan2(eb.dot(r_b.cross(v)), r_b.dot(v));
}

Eigen::Matrix<double, 3, 18> relative_angular_velocity_jacobian(const Eigen::VectorXd& y) {
  Eigen::Matrix<double, 3, 18> J;
  for (int k = 0; k < 3; ++k) {
    J.block<3, 3>(0, 3 * k) = 0.5 * cross_matrix(y.segment<3>(3 * k));
    J.block<3, 3>(0, 9 + 3 * k) = -0.5 * cross_matrix(y.segment<3>(9 + 3 * k));
  }
  return J;
}

double measure(JointMeasure kind, const Eigen::VectorXd& y) {
  const Vector3d a = y.segment<3>(0), b = y.segment<3>(3);
  switch (kind) {
    case JointMeasure::Distance: return (a - b).norm();
    case JointMeasure::Slide: {
      const Vector3d u = y.segment<3>(6);
      return (a - b).dot(u) / u.norm();
    }
    case JointMeasure::OffAxis: {
      const Vector3d r = a - b, u = y.segment<3>(6);
      const double c = r.dot(u);
      return r.squaredNorm() - c * c / u.squaredNorm();
    }
    case JointMeasure::HingeAngle: {
      const Vector3d n = y.segment<3>(6);
      return std::atan2(n.dot(b.cross(a)), a.dot(b));
    }
    case JointMeasure::BendAngle: return std::atan2(a.cross(b).norm(), a.dot(b));
    case JointMeasure::TwistAngle: return twist_angle(a, b, y.segment<3>(6), y.segment<3>(9));
  }
  return 0;
}

MeasureValue measure_derivatives(JointMeasure kind, const Eigen::VectorXd& y) {
  MeasureValue out;
  out.s = measure(kind, y);
  const Vector3d a = y.segment<3>(0), b = y.segment<3>(3);
  const Matrix3d I = Matrix3d::Identity();
  switch (kind) {
    case JointMeasure::Distance: {
      const Vector3d r = a - b;
      const double l = r.norm();
      const Vector3d rh = r / l;
      const Matrix3d P = (I - rh * rh.transpose()) / l;
      out.grad.resize(6);
      out.grad << rh, -rh;
      out.hess.resize(6, 6);
      out.hess << P, -P, -P, P;
      break;
    }
    case JointMeasure::Slide: {
      const Vector3d r = a - b, u = y.segment<3>(6);
      const double m = u.norm(), c = r.dot(u);
      const Vector3d uh = u / m;
      const Vector3d g_u = r / m - c * u / (m * m * m);
      const Matrix3d H_ru = (I - uh * uh.transpose()) / m;
      const Matrix3d H_uu = -(r * u.transpose() + u * r.transpose() + c * I) / (m * m * m) +
                            3 * c * u * u.transpose() / std::pow(m, 5);
      from_r_u(uh, g_u, Matrix3d::Zero(), H_ru, H_uu, out);
      break;
    }
    case JointMeasure::OffAxis: {
      const Vector3d r = a - b, u = y.segment<3>(6);
      const double m = u.squaredNorm(), c = r.dot(u);
      const Vector3d g_r = 2 * r - 2 * c * u / m;
      const Vector3d g_u = -2 * c * r / m + 2 * c * c * u / (m * m);
      const Matrix3d H_rr = 2 * I - 2 * u * u.transpose() / m;
      const Matrix3d H_ru = -2 * (u * r.transpose() / m + c * I / m - 2 * c * u * u.transpose() / (m * m));
      const Matrix3d H_uu = -2 * r * r.transpose() / m + 4 * c * (r * u.transpose() + u * r.transpose()) / (m * m) +
                            2 * c * c * I / (m * m) - 8 * c * c * u * u.transpose() / (m * m * m);
      from_r_u(g_r, g_u, H_rr, H_ru, H_uu, out);
      break;
    }
    case JointMeasure::HingeAngle: {
      // θ = atan2(S, C), S = n·(e_b × e_a), C = e_a·e_b; y = [e_a; e_b; n].
      const Vector3d n = y.segment<3>(6);
      const double S = n.dot(b.cross(a)), C = a.dot(b), rho = S * S + C * C;
      Eigen::Matrix<double, 9, 1> gS, gC;
      gS << n.cross(b), a.cross(n), b.cross(a);
      gC << b, a, Vector3d::Zero();
      Eigen::Matrix<double, 9, 9> HS = Eigen::Matrix<double, 9, 9>::Zero(), HC = HS;
      HS.block<3, 3>(0, 3) = cross_matrix(n);
      HS.block<3, 3>(0, 6) = -cross_matrix(b);
      HS.block<3, 3>(3, 6) = cross_matrix(a);
      HS.block<3, 3>(3, 0) = HS.block<3, 3>(0, 3).transpose();
      HS.block<3, 3>(6, 0) = HS.block<3, 3>(0, 6).transpose();
      HS.block<3, 3>(6, 3) = HS.block<3, 3>(3, 6).transpose();
      HC.block<3, 3>(0, 3) = I;
      HC.block<3, 3>(3, 0) = I;
      const Eigen::Matrix<double, 9, 1> g = (C * gS - S * gC) / rho;
      Eigen::Matrix<double, 9, 9> H = (gS * gC.transpose() - gC * gS.transpose() + C * HS - S * HC) / rho -
                                      2 * g * (S * gS + C * gC).transpose() / rho;
      out.grad = g;
      out.hess = 0.5 * (H + H.transpose());
      break;
    }
    case JointMeasure::BendAngle: from_dual(bend_dual(y), out); break;
    case JointMeasure::TwistAngle: from_dual(twist_dual(y), out); break;
  }
  return out;
}

}  // namespace stiffsoft
