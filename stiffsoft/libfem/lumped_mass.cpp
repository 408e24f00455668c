#include <stiffsoft/libfem/lumped_mass.hpp>

#include <stdexcept>
#include <string>

#include <stiffsoft/libfem/lame_parameters.hpp>
#include <stiffsoft/libfem/tet_element.hpp>

namespace stiffsoft::fem {

Eigen::VectorXd lumped_mass(const Eigen::MatrixX3d& X, const Eigen::MatrixX4i& T, double rho) {
  check_density(rho);
  Eigen::VectorXd m = Eigen::VectorXd::Zero(X.rows());
  for (Eigen::Index e = 0; e < T.rows(); ++e) {
    Vector12d Xe;
    for (int a = 0; a < 4; ++a) {
      const int v = T(e, a);
      if (v < 0 || v >= X.rows())
        throw std::invalid_argument("libfem: lumped_mass: tetrahedron " + std::to_string(e) +
                                    " has node index " + std::to_string(v) + "; expected 0 <= index < " +
                                    std::to_string(X.rows()));
      Xe.segment<3>(3 * a) = X.row(v).transpose();
    }
    const double quarter = rho * make_tet_element(Xe, int(e)).volume / 4;
    for (int a = 0; a < 4; ++a) m[T(e, a)] += quarter;
  }
  return m;
}

}  // namespace stiffsoft::fem
