#pragma once
/// @file The eigen-decomposition of a small symmetric matrix of fixed size in plain loops:
/// Householder tridiagonalisation, then the implicit QL method with Wilkinson's shift
/// (EISPACK's tred2 and tql2; Golub & Van Loan, Matrix Computations, §8.3). For the 3×3 to
/// 5×5 matrices of the barrier's projection (projected_barrier_hessian.cpp) and the 3×3 to
/// 9×9 ones of the mollified edge pairs' (psd_projection.cpp) the compiler unrolls it, where
/// Eigen's SelfAdjointEigenSolver runs its general blocked code: 0.89 µs against 1.32 µs for a
/// 5×5 (docs/benchmarks.md, session 25), 3.8 µs against 6.0 µs for a 9×9 (session 35;
/// bench/symmetric_eigen_bench.cpp).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

namespace stiffsoft::contact {

/// A = V diag(λ) Vᵀ; `converged` is false when the QL iteration did not settle (λ and V are
/// then not to be used).
template <int N>
struct SymmetricEigen {
  Eigen::Matrix<double, N, 1> values;   ///< λ, in no particular order
  Eigen::Matrix<double, N, N> vectors;  ///< V: orthonormal columns, column m for λ_m
  bool converged = true;                ///< whether every eigenvalue converged
};

/// The eigen-decomposition of the symmetric N×N matrix whose lower triangle A holds.
template <int N>
SymmetricEigen<N> symmetric_eigen(const Eigen::Matrix<double, N, N>& A) {
  SymmetricEigen<N> out;
  Eigen::Matrix<double, N, N>& Q = out.vectors;  // A's lower triangle, then the reflections, then V
  Q = A;
  Eigen::Matrix<double, N, 1>& diag = out.values;
  Eigen::Matrix<double, N, 1> sub;  // sub(i): the tridiagonal entry (i, i − 1)
  Eigen::Matrix<double, N, 1> h;    // h(i): the i-th reflection's ½‖u‖² (0: none)
  // 1. Rows N − 1 … 1: a reflection I − u uᵀ / h on the indices 0 … i − 1 zeroes row i left of
  //    its sub-diagonal; u is kept in row i, u / h in column i.
  for (int i = N - 1; i > 0; --i) {
    const int l = i - 1;
    double scale = 0;
    for (int k = 0; k <= l; ++k) scale += std::abs(Q(i, k));
    h(i) = 0;
    if (l == 0 || scale == 0.0) {
      sub(i) = Q(i, l);
      continue;
    }
    double norm2 = 0;
    for (int k = 0; k <= l; ++k) {
      Q(i, k) /= scale;
      norm2 += Q(i, k) * Q(i, k);
    }
    const double f = Q(i, l), g = f >= 0 ? -std::sqrt(norm2) : std::sqrt(norm2);
    sub(i) = scale * g;
    h(i) = norm2 - f * g;
    Q(i, l) = f - g;
    // p = A u / h, then K = uᵀp / 2h and A ← A − u qᵀ − q uᵀ with q = p − K u.
    Eigen::Matrix<double, N, 1> p;
    double upu = 0;
    for (int j = 0; j <= l; ++j) {
      Q(j, i) = Q(i, j) / h(i);
      double Au = 0;
      for (int k = 0; k <= j; ++k) Au += Q(j, k) * Q(i, k);
      for (int k = j + 1; k <= l; ++k) Au += Q(k, j) * Q(i, k);
      p(j) = Au / h(i);
      upu += p(j) * Q(i, j);
    }
    const double K = upu / (2 * h(i));
    for (int j = 0; j <= l; ++j) {
      const double u_j = Q(i, j);
      p(j) -= K * u_j;
      for (int k = 0; k <= j; ++k) Q(j, k) -= u_j * p(k) + p(j) * Q(i, k);
    }
  }
  // 2. The tridiagonal's diagonal, and the product of the reflections accumulated into Q.
  sub(0) = 0;
  for (int i = 0; i < N; ++i) {
    if (i > 0 && h(i) != 0.0)
      for (int j = 0; j < i; ++j) {
        double g = 0;
        for (int k = 0; k < i; ++k) g += Q(i, k) * Q(k, j);
        for (int k = 0; k < i; ++k) Q(k, j) -= g * Q(k, i);
      }
    diag(i) = Q(i, i);
    Q(i, i) = 1;
    for (int j = 0; j < i; ++j) Q(j, i) = Q(i, j) = 0;
  }
  // 3. Implicit QL sweeps on the tridiagonal (off-diagonal e(i) = entry (i + 1, i)), each
  //    rotation also applied to Q's columns, until every off-diagonal entry is negligible:
  //    below ε times the tridiagonal's norm (tql2's test). The reduction's rounding already
  //    perturbs every eigenvalue by that much, and a test relative to the neighbouring
  //    diagonal entries instead spent 5 % more time on the 5×5 matrices of the barrier's
  //    projection (30 rotations each against 28) polishing eigenvalues near zero.
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  Eigen::Matrix<double, N, 1> e;
  for (int i = 0; i + 1 < N; ++i) e(i) = sub(i + 1);
  e(N - 1) = 0;
  double norm = 0;  // ‖T‖∞
  for (int i = 0; i < N; ++i) norm = std::max(norm, std::abs(diag(i)) + std::abs(sub(i)) + std::abs(e(i)));
  const double negligible = kEpsilon * norm;
  for (int l = 0; l < N; ++l) {
    for (int iteration = 0;; ++iteration) {
      int m = l;
      while (m + 1 < N && std::abs(e(m)) > negligible) ++m;
      if (m == l) break;
      if (iteration == 60) {
        out.converged = false;
        return out;
      }
      // Wilkinson's shift from the leading 2×2, then chase the bulge from m up to l.
      double g = (diag(l + 1) - diag(l)) / (2 * e(l));
      double r = std::sqrt(g * g + 1);
      g = diag(m) - diag(l) + e(l) / (g + (g >= 0 ? r : -r));
      double s = 1, c = 1, p = 0;
      int i = m - 1;
      for (; i >= l; --i) {
        const double f = s * e(i), b = c * e(i);
        r = std::sqrt(f * f + g * g);
        e(i + 1) = r;
        if (r == 0.0) {  // the matrix split: deflate and start again
          diag(i + 1) -= p;
          e(m) = 0;
          break;
        }
        s = f / r;
        c = g / r;
        g = diag(i + 1) - p;
        r = (diag(i) - g) * s + 2 * c * b;
        p = s * r;
        diag(i + 1) = g + p;
        g = c * r - b;
        for (int k = 0; k < N; ++k) {
          const double q = Q(k, i + 1);
          Q(k, i + 1) = s * Q(k, i) + c * q;
          Q(k, i) = c * Q(k, i) - s * q;
        }
      }
      if (r == 0.0 && i >= l) continue;
      diag(l) -= p;
      e(l) = g;
      e(m) = 0;
    }
  }
  return out;
}

/// symmetric_eigen(A), or Eigen's SelfAdjointEigenSolver where its QL iteration does not
/// settle: always converged. Defined in symmetric_eigen.cpp (Eigen's fixed-size solver costs
/// every file that instantiates it inline about half a minute of compile time) for N = 3, 4, 5
/// (the barrier's projection in the distance span) and 6, 9 (the mollified edge pairs').
template <int N>
SymmetricEigen<N> checked_symmetric_eigen(const Eigen::Matrix<double, N, N>& A);

}  // namespace stiffsoft::contact
