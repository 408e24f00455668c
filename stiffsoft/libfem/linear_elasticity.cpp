#include <stiffsoft/libfem/linear_elasticity.hpp>

namespace stiffsoft::fem {

namespace {
Eigen::Matrix3d small_strain(const Eigen::Matrix3d& F) {
  return 0.5 * (F + F.transpose()) - Eigen::Matrix3d::Identity();
}
}  // namespace

LinearElasticity::LinearElasticity(double E, double nu) : Material(E, nu) {
  const double mu = lame().mu, lambda = lame().lambda;
  m_dPdF.setZero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          m_dPdF(i + 3 * j, k + 3 * l) =
              mu * ((i == k && j == l) + (i == l && j == k)) + lambda * (i == j && k == l);
}

double LinearElasticity::psi(const Eigen::Matrix3d& F) const {
  const Eigen::Matrix3d eps = small_strain(F);
  const double tr = eps.trace();
  return lame().mu * eps.squaredNorm() + 0.5 * lame().lambda * tr * tr;
}

Eigen::Matrix3d LinearElasticity::P(const Eigen::Matrix3d& F) const {
  const Eigen::Matrix3d eps = small_strain(F);
  return 2 * lame().mu * eps + lame().lambda * eps.trace() * Eigen::Matrix3d::Identity();
}

Matrix9d LinearElasticity::dPdF(const Eigen::Matrix3d&) const { return m_dPdF; }

}  // namespace stiffsoft::fem
