#include <stiffsoft/libfem/material.hpp>

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include <stiffsoft/libfem/project_psd.hpp>

namespace stiffsoft::fem {

Material::Material(double E, double nu) : m_E(E), m_nu(nu), m_lame(lame_parameters(E, nu)) {}

Matrix9d Material::dPdF_projected(const Eigen::Matrix3d& F) const { return project_psd<9>(dPdF(F)); }

double Material::von_mises(const Eigen::Matrix3d& F) const {
  const double J = std::abs(F.determinant());
  if (J == 0) return std::numeric_limits<double>::infinity();
  const Eigen::Matrix3d sigma = P(F) * F.transpose() / J;
  const Eigen::Matrix3d s = sigma - sigma.trace() / 3 * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * s.squaredNorm());
}

}  // namespace stiffsoft::fem
