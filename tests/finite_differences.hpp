#pragma once
/// @file Central finite differences for the conformance tests of every potential.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <functional>

namespace stiffsoft::testing {

/// Central-difference gradient of f at x with step h.
inline Eigen::VectorXd fd_gradient(const std::function<double(const Eigen::VectorXd&)>& f,
                                   const Eigen::VectorXd& x, double h = 1e-6) {
  Eigen::VectorXd g(x.size());
  Eigen::VectorXd y = x;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    y[i] = x[i] + h;
    const double fp = f(y);
    y[i] = x[i] - h;
    const double fm = f(y);
    y[i] = x[i];
    g[i] = (fp - fm) / (2 * h);
  }
  return g;
}

/// Central-difference Jacobian of the vector function g at x (the Hessian when g is a gradient).
inline Eigen::MatrixXd fd_jacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& g, const Eigen::VectorXd& x,
    double h = 1e-6) {
  const Eigen::Index m = g(x).size();
  Eigen::MatrixXd J(m, x.size());
  Eigen::VectorXd y = x;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    y[i] = x[i] + h;
    const Eigen::VectorXd gp = g(y);
    y[i] = x[i] - h;
    const Eigen::VectorXd gm = g(y);
    y[i] = x[i];
    J.col(i) = (gp - gm) / (2 * h);
  }
  return J;
}

/// Relative error ‖a − b‖ / max(‖b‖, floor), the measure every conformance test uses.
inline double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                             double floor = 1e-12) {
  return (a - b).norm() / std::max(b.norm(), floor);
}

/// Smallest eigenvalue of the symmetric part of H.
inline double min_eigenvalue(const Eigen::MatrixXd& H) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (H + H.transpose()));
  return es.eigenvalues().minCoeff();
}

}  // namespace stiffsoft::testing
