#include <stiffsoft/libfem/rotation_variant_svd.hpp>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace stiffsoft::fem {

namespace {

/// One-sided (Hestenes) Jacobi: rotates pairs of columns of B = F V until they are orthogonal
/// to working precision, accumulating the rotations in V. Then B's columns are U Σ. Each
/// rotation makes one pair orthogonal; convergence is quadratic, so a 3×3 near a rotation
/// takes three or four sweeps of three rotations. ‖B‖² must lie within about 1e±100: the
/// test multiplies squared column norms.
void orthogonalise_columns(Eigen::Matrix3d& B, Eigen::Matrix3d& V) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  constexpr int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int sweep = 0; sweep < 30; ++sweep) {
    bool rotated = false;
    for (const auto& [p, q] : pairs) {
      const double alpha = B.col(p).squaredNorm(), beta = B.col(q).squaredNorm();
      const double gamma = B.col(p).dot(B.col(q));
      if (!(gamma * gamma > eps * eps * alpha * beta)) continue;
      rotated = true;
      // tan of the angle that zeroes the pair's off-diagonal entry of BᵀB: the smaller root of
      // t² + 2ζt − 1 = 0 (1/(2ζ) where ζ² would overflow).
      const double zeta = (beta - alpha) / (2 * gamma);
      const double t = std::abs(zeta) > 1e150 ? 0.5 / zeta
                                              : std::copysign(1.0, zeta) / (std::abs(zeta) + std::sqrt(1 + zeta * zeta));
      const double c = 1 / std::sqrt(1 + t * t), s = c * t;
      for (Eigen::Matrix3d* M : {&B, &V}) {
        const Eigen::Vector3d mp = M->col(p), mq = M->col(q);
        M->col(p) = c * mp - s * mq;
        M->col(q) = s * mp + c * mq;
      }
    }
    if (!rotated) return;
  }
}

/// A unit vector orthogonal to the unit vector u.
Eigen::Vector3d orthogonal_unit(const Eigen::Vector3d& u) {
  int smallest;
  u.cwiseAbs().minCoeff(&smallest);
  return u.cross(Eigen::Vector3d::Unit(smallest)).normalized();
}

}  // namespace

RotationVariantSvd rotation_variant_svd(const Eigen::Matrix3d& F) {
  RotationVariantSvd out{F, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
  Eigen::Matrix3d& B = out.U;
  // Magnitudes whose squared products would overflow or underflow are scaled to 1 for the
  // rotations, and σ back.
  const double size2 = F.squaredNorm();
  const bool rescale = size2 > 1e100 || (size2 > 0 && size2 < 1e-100);
  const double size = rescale ? std::sqrt(size2) : 1.0;
  if (rescale) B /= size;
  orthogonalise_columns(B, out.V);
  for (int i = 0; i < 3; ++i) out.sigma(i) = B.col(i).norm();
  // Sort by decreasing σ (three compare-and-swaps), moving the columns of B and V along.
  const auto order = [&](int i, int j) {
    if (out.sigma(i) >= out.sigma(j)) return;
    std::swap(out.sigma(i), out.sigma(j));
    B.col(i).swap(B.col(j));
    out.V.col(i).swap(out.V.col(j));
  };
  order(0, 1);
  order(0, 2);
  order(1, 2);
  // U's columns are B's normalised; a zero σ leaves its column to complete the basis.
  if (out.sigma(0) == 0) {
    out.U.setIdentity();
  } else {
    B.col(0) /= out.sigma(0);
    if (out.sigma(1) > 0) B.col(1) /= out.sigma(1);
    else B.col(1) = orthogonal_unit(B.col(0));
    if (out.sigma(2) > 0) B.col(2) /= out.sigma(2);
    else B.col(2) = B.col(0).cross(B.col(1));
  }
  if (rescale) out.sigma *= size;
  // Flipping the last column of U (or V) and the sign of the smallest σ keeps F = U Σ Vᵀ; the
  // smallest one, so that the polar rotation R = U Vᵀ is the closest rotation to F.
  if (out.U.determinant() < 0) {
    out.U.col(2) *= -1;
    out.sigma(2) *= -1;
  }
  if (out.V.determinant() < 0) {
    out.V.col(2) *= -1;
    out.sigma(2) *= -1;
  }
  return out;
}

}  // namespace stiffsoft::fem
