#include <stiffsoft/libfem/determinant_derivatives.hpp>

#include <Eigen/Geometry>

namespace stiffsoft::fem {

namespace {
/// [a]×, the matrix with [a]× b = a × b.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d A;
  A << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return A;
}
}  // namespace

Eigen::Matrix3d cofactor(const Eigen::Matrix3d& F) {
  Eigen::Matrix3d C;
  C.col(0) = F.col(1).cross(F.col(2));
  C.col(1) = F.col(2).cross(F.col(0));
  C.col(2) = F.col(0).cross(F.col(1));
  return C;
}

Matrix9d determinant_hessian(const Eigen::Matrix3d& F) {
  // Block (a, b) is ∂(column a of cof F)/∂f_b; e.g. f₁ × f₂ = −[f₂]× f₁ = [f₁]× f₂.
  const Eigen::Matrix3d f0 = cross_matrix(F.col(0)), f1 = cross_matrix(F.col(1)), f2 = cross_matrix(F.col(2));
  Matrix9d H = Matrix9d::Zero();
  H.block<3, 3>(0, 3) = -f2;
  H.block<3, 3>(0, 6) = f1;
  H.block<3, 3>(3, 0) = f2;
  H.block<3, 3>(3, 6) = -f0;
  H.block<3, 3>(6, 0) = -f1;
  H.block<3, 3>(6, 3) = f0;
  return H;
}

void add_determinant_hessian(double s, const Eigen::Matrix3d& F, Matrix9d& H) {
  // Block (a, b), b = a + 1 or a + 2 (mod 3), is ±[f_k]× with k the third column: + for
  // (0, 6), (3, 0), (6, 3), − for (0, 3), (3, 6), (6, 0). [f]× has f_z at (1, 0), −f_z at (0, 1), …
  const auto add_cross = [&](int row, int column, double sign, const Eigen::Vector3d& f) {
    const Eigen::Vector3d sf = s * (sign * f);
    H(row + 1, column) += sf.z();
    H(row, column + 1) -= sf.z();
    H(row, column + 2) += sf.y();
    H(row + 2, column) -= sf.y();
    H(row + 2, column + 1) += sf.x();
    H(row + 1, column + 2) -= sf.x();
  };
  add_cross(0, 3, -1, F.col(2));
  add_cross(0, 6, 1, F.col(1));
  add_cross(3, 0, 1, F.col(2));
  add_cross(3, 6, -1, F.col(0));
  add_cross(6, 0, -1, F.col(1));
  add_cross(6, 3, 1, F.col(0));
}

}  // namespace stiffsoft::fem
