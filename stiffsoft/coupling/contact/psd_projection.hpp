#pragma once
/// @file Projection of symmetric stencil Hessians onto the positive semi-definite cone.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace stiffsoft::contact {

/// Nearest (Frobenius) positive semi-definite matrix to the symmetric N×N matrix A:
/// A = V Λ Vᵀ → V max(Λ, 0) Vᵀ (projected Newton, Teran et al. 2005; IPC §4).
/// Reads the lower triangle of A. Returns A itself, bit for bit, when it is already PSD,
/// so that projecting a PSD Hessian never perturbs it.
template <int N>
Eigen::Matrix<double, N, N> project_to_psd(const Eigen::Matrix<double, N, N>& A) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> es(A);
  const auto& lambda = es.eigenvalues();
  if (lambda.minCoeff() >= 0.0) return A;
  const auto& V = es.eigenvectors();
  return V * lambda.cwiseMax(0.0).asDiagonal() * V.transpose();
}

/// Projects the leading (3·n)×(3·n) block of a stencil Hessian (n = active vertices, 1..4) to
/// PSD in place; the rest is zero by construction for contact stencils and stays untouched.
/// Projecting only the active block is cheaper and gives the same result as the full 12×12.
inline void project_leading_block_to_psd(Eigen::Matrix<double, 12, 12>& H, int active_vertices) {
  switch (active_vertices) {
    case 1: H.topLeftCorner<3, 3>() = project_to_psd<3>(H.topLeftCorner<3, 3>()); break;
    case 2: H.topLeftCorner<6, 6>() = project_to_psd<6>(H.topLeftCorner<6, 6>()); break;
    case 3: H.topLeftCorner<9, 9>() = project_to_psd<9>(H.topLeftCorner<9, 9>()); break;
    default: H = project_to_psd<12>(H); break;
  }
}

}  // namespace stiffsoft::contact
