#include <stiffsoft/libfem/tet_element.hpp>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <stiffsoft/libfem/format_number.hpp>

namespace stiffsoft::fem {

TetElement make_tet_element(const Vector12d& X, int index) {
  const Eigen::Matrix3d D_m = deformed_shape_matrix(X);
  double longest = 0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b)
      longest = std::max(longest, (X.segment<3>(3 * b) - X.segment<3>(3 * a)).norm());
  const double volume = std::abs(D_m.determinant()) / 6;
  // Scale-free test: a sliver with V ≤ 1e-12 ℓ³ has a D_m whose inverse is numerically meaningless.
  if (!(volume > 1e-12 * longest * longest * longest))
    throw std::invalid_argument("libfem: tetrahedron " + std::to_string(index) +
                                " is degenerate: rest volume " + format_number(volume) +
                                " m^3 with longest edge " + format_number(longest) +
                                " m; expected a volume > 1e-12 * edge^3");
  return {D_m.inverse(), volume};
}

Eigen::Matrix3d deformed_shape_matrix(const Vector12d& x) {
  Eigen::Matrix3d D;
  for (int a = 0; a < 3; ++a) D.col(a) = x.segment<3>(3 * (a + 1)) - x.segment<3>(0);
  return D;
}

Eigen::Matrix3d deformation_gradient(const TetElement& element, const Vector12d& x) {
  return deformed_shape_matrix(x) * element.D_m_inv;
}

Matrix9x12d deformation_gradient_jacobian(const TetElement& element) {
  const Eigen::Matrix3d& B = element.D_m_inv;
  const Eigen::RowVector3d b0 = -B.colwise().sum();
  Matrix9x12d dFdx = Matrix9x12d::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      dFdx(i + 3 * j, i) = b0(j);
      for (int a = 1; a < 4; ++a) dFdx(i + 3 * j, 3 * a + i) = B(a - 1, j);
    }
  return dFdx;
}

double tet_energy(const TetElement& element, const Material& material, const Vector12d& x) {
  return element.volume * material.psi(deformation_gradient(element, x));
}

Vector12d tet_gradient(const TetElement& element, const Material& material, const Vector12d& x) {
  const Eigen::Matrix3d P = material.P(deformation_gradient(element, x));
  // ∂(Vψ)/∂x_a = V P D_m⁻ᵀ e_{a−1} for a = 1..3; node 0 balances the other three.
  const Eigen::Matrix3d H = element.volume * P * element.D_m_inv.transpose();
  Vector12d g;
  g.segment<3>(0) = -H.rowwise().sum();
  for (int a = 1; a < 4; ++a) g.segment<3>(3 * a) = H.col(a - 1);
  return g;
}

Matrix12d tet_hessian(const TetElement& element, const Material& material, const Vector12d& x,
                      bool project_psd) {
  Matrix12d H;
  tet_hessian(element, material, x, project_psd, 1.0, H);
  return H;
}

void tet_hessian(const TetElement& element, const Material& material, const Vector12d& x, bool project_psd,
                 double weight, Matrix12d& H) {
  const Matrix9d dPdF = material.dPdF(deformation_gradient(element, x), project_psd);
  // (∂F/∂x)ᵀ ∂P/∂F ∂F/∂x without forming ∂F/∂x: ∂F_ij/∂x_{a,i} = β_a[j] with β_a (a = 1..3) the
  // rows of D_m⁻¹, so block (a, b) = w V Σ_{j,l} β_a[j] β_b[l] (∂P/∂F)_{jl}, (∂P/∂F)_{jl} the 3×3
  // block at rows 3j, columns 3l. Node 0's β_0 = −(β_1 + β_2 + β_3) makes its blocks the
  // negated sums of the others': the nine blocks of nodes 1..3 are formed (six, the matrix being
  // symmetric), the rest summed.
  const Eigen::Matrix3d& beta = element.D_m_inv;
  const double w_volume = weight * element.volume;
  std::array<Eigen::Matrix<double, 3, 9>, 3> T;  // T_a = w V Σ_j β_a[j] (rows 3j..3j+2 of ∂P/∂F)
  for (int a = 0; a < 3; ++a) {
    T[a] = w_volume * beta(a, 0) * dPdF.middleRows<3>(0);
    for (int j = 1; j < 3; ++j) T[a] += w_volume * beta(a, j) * dPdF.middleRows<3>(3 * j);
  }
  for (int a = 1; a < 4; ++a)
    for (int b = a; b < 4; ++b) {
      Eigen::Matrix3d H_ab = beta(b - 1, 0) * T[a - 1].leftCols<3>();
      for (int l = 1; l < 3; ++l) H_ab += beta(b - 1, l) * T[a - 1].middleCols<3>(3 * l);
      H.block<3, 3>(3 * a, 3 * b) = H_ab;
      if (b != a) H.block<3, 3>(3 * b, 3 * a) = H_ab.transpose();
    }
  for (int a = 1; a < 4; ++a) {
    const Eigen::Matrix3d H_a0 = -(H.block<3, 3>(3 * a, 3) + H.block<3, 3>(3 * a, 6) + H.block<3, 3>(3 * a, 9));
    H.block<3, 3>(3 * a, 0) = H_a0;
    H.block<3, 3>(0, 3 * a) = H_a0.transpose();
  }
  H.block<3, 3>(0, 0) = -(H.block<3, 3>(3, 0) + H.block<3, 3>(6, 0) + H.block<3, 3>(9, 0));
}

}  // namespace stiffsoft::fem
