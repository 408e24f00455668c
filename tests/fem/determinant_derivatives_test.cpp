// The in-place ∂²J/∂F² that materials add against the formed 9×9, and the formed one against
// finite differences of cof F.
#include <gtest/gtest.h>

#include <random>

#include <stiffsoft/libfem/determinant_derivatives.hpp>

using namespace stiffsoft::fem;

TEST(DeterminantHessian, IsTheDerivativeOfTheCofactor) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix3d F;
  for (int i = 0; i < 9; ++i) F.data()[i] = u(rng);
  const Matrix9d H = determinant_hessian(F);
  const double h = 1e-6;
  for (int k = 0; k < 9; ++k) {  // cof F is quadratic in F: central differences are exact but for rounding
    Eigen::Matrix3d plus = F, minus = F;
    plus.data()[k] += h;
    minus.data()[k] -= h;
    const Vector9d column = (vec(cofactor(plus)) - vec(cofactor(minus))) / (2 * h);
    EXPECT_LT((H.col(k) - column).norm(), 1e-8) << "column " << k;
  }
}

TEST(DeterminantHessian, AddedInPlaceEqualsAddingTheFormedMatrixBitForBit) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Matrix3d F;
    for (int i = 0; i < 9; ++i) F.data()[i] = u(rng);
    Matrix9d start;
    for (int i = 0; i < 81; ++i) start.data()[i] = u(rng);
    const double s = u(rng);
    const Matrix9d expected = start + s * determinant_hessian(F);
    Matrix9d in_place = start;
    add_determinant_hessian(s, F, in_place);
    EXPECT_TRUE(in_place == expected) << "trial " << trial << ":\n" << in_place - expected;
  }
}
