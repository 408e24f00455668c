#pragma once
/// @file Forward-mode second-order automatic differentiation: a scalar that carries its value,
/// gradient and Hessian in N variables and propagates them by the chain rule. The joint
/// measures whose hand-written Hessians would be long (bend and twist angles of cone-twist
/// joints, joint_measures.hpp) are written once over this type; tests check the result against
/// finite differences.

#include <Eigen/Core>
#include <cmath>

namespace stiffsoft {

/// f(y), ∇f and ∇²f for y ∈ ℝᴺ.
template <int N>
struct Dual2 {
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  double v = 0;                     ///< value
  Vector g = Vector::Zero();        ///< gradient
  Matrix H = Matrix::Zero();        ///< Hessian (symmetric)

  /// A constant.
  static Dual2 constant(double value) {
    Dual2 d;
    d.v = value;
    return d;
  }
  /// The i-th variable, at `value`.
  static Dual2 variable(int i, double value) {
    Dual2 d;
    d.v = value;
    d.g[i] = 1;
    return d;
  }
  /// f(self) for a scalar function with f = f0, f' = f1, f'' = f2 at self's value.
  Dual2 chain(double f0, double f1, double f2) const {
    Dual2 d;
    d.v = f0;
    d.g = f1 * g;
    d.H = f1 * H + f2 * g * g.transpose();
    return d;
  }
};

/// a + b.
template <int N>
Dual2<N> operator+(const Dual2<N>& a, const Dual2<N>& b) {
  Dual2<N> d;
  d.v = a.v + b.v;
  d.g = a.g + b.g;
  d.H = a.H + b.H;
  return d;
}
/// a − b.
template <int N>
Dual2<N> operator-(const Dual2<N>& a, const Dual2<N>& b) {
  Dual2<N> d;
  d.v = a.v - b.v;
  d.g = a.g - b.g;
  d.H = a.H - b.H;
  return d;
}
/// −a.
template <int N>
Dual2<N> operator-(const Dual2<N>& a) {
  Dual2<N> d;
  d.v = -a.v;
  d.g = -a.g;
  d.H = -a.H;
  return d;
}
/// a b.
template <int N>
Dual2<N> operator*(const Dual2<N>& a, const Dual2<N>& b) {
  Dual2<N> d;
  d.v = a.v * b.v;
  d.g = a.v * b.g + b.v * a.g;
  d.H = a.v * b.H + b.v * a.H + a.g * b.g.transpose() + b.g * a.g.transpose();
  return d;
}
/// s a for a constant s.
template <int N>
Dual2<N> operator*(double s, const Dual2<N>& a) {
  Dual2<N> d;
  d.v = s * a.v;
  d.g = s * a.g;
  d.H = s * a.H;
  return d;
}
/// a / b (b ≠ 0).
template <int N>
Dual2<N> operator/(const Dual2<N>& a, const Dual2<N>& b) {
  const double inv = 1 / b.v;
  return a * b.chain(inv, -inv * inv, 2 * inv * inv * inv);
}
/// √a (a > 0).
template <int N>
Dual2<N> sqrt(const Dual2<N>& a) {
  const double r = std::sqrt(a.v);
  return a.chain(r, 0.5 / r, -0.25 / (r * a.v));
}
/// atan2(y, x) ((x, y) ≠ 0): the angle of (x, y), in (−π, π].
template <int N>
Dual2<N> atan2(const Dual2<N>& y, const Dual2<N>& x) {
  const double rho = x.v * x.v + y.v * y.v;
  Dual2<N> d;
  d.v = std::atan2(y.v, x.v);
  // θ' = (x y' − y x')/ρ; θ'' from the quotient rule with ρ' = 2 (x x' + y y').
  d.g = (x.v * y.g - y.v * x.g) / rho;
  d.H = (x.g * y.g.transpose() - y.g * x.g.transpose() + x.v * y.H - y.v * x.H) / rho -
        2 * d.g * (x.v * x.g + y.v * y.g).transpose() / rho;
  d.H = 0.5 * (d.H + d.H.transpose()).eval();
  return d;
}

/// A 3-vector of Dual2 scalars, with the vector algebra the measures need.
template <int N>
struct Dual2Vector3 {
  Dual2<N> x, y, z;  ///< components
  /// The three variables 3k, 3k + 1, 3k + 2 at `value`.
  static Dual2Vector3 variables(int k, const Eigen::Vector3d& value) {
    return {Dual2<N>::variable(3 * k, value.x()), Dual2<N>::variable(3 * k + 1, value.y()),
            Dual2<N>::variable(3 * k + 2, value.z())};
  }
};

/// a + b.
template <int N>
Dual2Vector3<N> operator+(const Dual2Vector3<N>& a, const Dual2Vector3<N>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
/// s a for a scalar s.
template <int N>
Dual2Vector3<N> operator*(const Dual2<N>& s, const Dual2Vector3<N>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
/// a · b.
template <int N>
Dual2<N> dot(const Dual2Vector3<N>& a, const Dual2Vector3<N>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
/// a × b.
template <int N>
Dual2Vector3<N> cross(const Dual2Vector3<N>& a, const Dual2Vector3<N>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/// a / |a| (a ≠ 0).
template <int N>
Dual2Vector3<N> normalized(const Dual2Vector3<N>& a) {
  const Dual2<N> inv = Dual2<N>::constant(1) / sqrt(dot(a, a));
  return inv * a;
}

}  // namespace stiffsoft
