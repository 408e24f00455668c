#include <stiffsoft/libfem/rotation_variant_svd.hpp>

#include <Eigen/LU>
#include <Eigen/SVD>

namespace stiffsoft::fem {

RotationVariantSvd rotation_variant_svd(const Eigen::Matrix3d& F) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  RotationVariantSvd out{svd.matrixU(), svd.singularValues(), svd.matrixV()};
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
