#include <stiffsoft/libfem/fixed_corotated.hpp>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include <stiffsoft/libfem/determinant_derivatives.hpp>
#include <stiffsoft/libfem/rotation_variant_svd.hpp>

namespace stiffsoft::fem {

FixedCorotated::FixedCorotated(double E, double nu) : Material(E, nu) {}

double FixedCorotated::psi(const Eigen::Matrix3d& F) const {
  const RotationVariantSvd svd = rotation_variant_svd(F);
  const double J = F.determinant();
  return lame().mu * (svd.sigma.array() - 1).square().sum() + 0.5 * lame().lambda * (J - 1) * (J - 1);
}

Eigen::Matrix3d FixedCorotated::P(const Eigen::Matrix3d& F) const {
  const RotationVariantSvd svd = rotation_variant_svd(F);
  const Eigen::Matrix3d R = svd.U * svd.V.transpose();
  return 2 * lame().mu * (F - R) + lame().lambda * (F.determinant() - 1) * cofactor(F);
}

Matrix9d FixedCorotated::dPdF(const Eigen::Matrix3d& F) const {
  const double mu = lame().mu, lambda = lame().lambda;
  const RotationVariantSvd svd = rotation_variant_svd(F);
  const Eigen::Vector3d& s = svd.sigma;
  const double floor = 1e-12 * (std::abs(s(0)) + 1);
  Matrix9d dRdF = Matrix9d::Zero();
  constexpr int pairs[3][2] = {{0, 1}, {1, 2}, {0, 2}};
  for (const auto& [i, j] : pairs) {
    Eigen::Matrix3d T = Eigen::Matrix3d::Zero();
    T(i, j) = 1 / std::sqrt(2.0);
    T(j, i) = -1 / std::sqrt(2.0);
    const Vector9d q = vec(svd.U * T * svd.V.transpose());
    // σ₀ ≥ σ₁ ≥ |σ₂| makes σᵢ + σⱼ ≥ 0; it is 0 only on the set where R is discontinuous.
    dRdF += 2 / std::max(s(i) + s(j), floor) * q * q.transpose();
  }
  const Vector9d g = vec(cofactor(F));
  return 2 * mu * (Matrix9d::Identity() - dRdF) + lambda * g * g.transpose() +
         lambda * (F.determinant() - 1) * determinant_hessian(F);
}

}  // namespace stiffsoft::fem
