#pragma once
/// @file Projection of a symmetric matrix onto the positive semi-definite cone (eigen-clamp).

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace stiffsoft::fem {

/// The nearest (Frobenius) positive semi-definite matrix to sym(H) = ½(H + Hᵀ):
/// Q max(Λ, 0) Qᵀ with sym(H) = Q Λ Qᵀ. Fixed size n (9 for ∂P/∂F, 12 for an element).
template <int n>
Eigen::Matrix<double, n, n> project_psd(const Eigen::Matrix<double, n, n>& H) {
  using Matrix = Eigen::Matrix<double, n, n>;
  const Matrix S = 0.5 * (H + H.transpose());
  const Eigen::SelfAdjointEigenSolver<Matrix> es(S);
  if (es.eigenvalues().minCoeff() >= 0) return S;
  const Eigen::Matrix<double, n, 1> lambda = es.eigenvalues().cwiseMax(0.0);
  return es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
}

}  // namespace stiffsoft::fem
