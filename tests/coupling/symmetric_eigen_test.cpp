/// symmetric_eigen (symmetric_eigen.hpp): the decomposition rebuilds the matrix with
/// orthonormal vectors and Eigen's eigenvalues, for random, repeated-eigenvalue, diagonal,
/// rank-one, zero and badly scaled matrices of the sizes the barrier's projections use (2 to 5
/// in the distance span, 3, 6 and 9 in the mollified edge pairs' translation complement).

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <random>
#include <vector>

#include <stiffsoft/coupling/contact/symmetric_eigen.hpp>

namespace stiffsoft::contact {
namespace {

/// Matrices of size N: random, with a repeated eigenvalue, diagonal, rank one, zero, and a
/// random one scaled to 1e12 (a stiff barrier's magnitude).
template <int N>
std::vector<Eigen::Matrix<double, N, N>> test_matrices(unsigned seed) {
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  const auto random = [&] {
    Matrix A;
    for (int i = 0; i < N * N; ++i) A.data()[i] = normal(rng);
    return Matrix(A + A.transpose());
  };
  std::vector<Matrix> out;
  for (int k = 0; k < 200; ++k) out.push_back(random());
  for (int k = 0; k < 50; ++k) {
    const Eigen::HouseholderQR<Matrix> qr(random());
    Vector lambda = Vector::Constant(-2.0);  // −2 repeated, then one 3
    lambda(N - 1) = 3.0;
    const Matrix Q = qr.householderQ();
    out.push_back(Q * lambda.asDiagonal() * Q.transpose());
  }
  Vector d;
  for (int i = 0; i < N; ++i) d(i) = i - 1.5;
  out.push_back(d.asDiagonal());
  Vector v;
  for (int i = 0; i < N; ++i) v(i) = normal(rng);
  out.push_back(v * v.transpose());
  out.push_back(Matrix::Zero());
  out.push_back(1e12 * random());
  return out;
}

template <int N>
void expect_decompositions(unsigned seed) {
  for (const auto& A : test_matrices<N>(seed)) {
    const SymmetricEigen<N> es = symmetric_eigen<N>(A);
    ASSERT_TRUE(es.converged);
    const double scale = std::max(A.norm(), 1e-300);
    EXPECT_LE((es.vectors * es.values.asDiagonal() * es.vectors.transpose() - A).norm(), 1e-14 * scale) << N;
    EXPECT_LE((es.vectors.transpose() * es.vectors - Eigen::Matrix<double, N, N>::Identity()).norm(), 1e-14) << N;
    Eigen::Matrix<double, N, 1> ours = es.values;
    std::sort(ours.data(), ours.data() + N);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eigen(A);  // ascending
    EXPECT_LE((ours - eigen.eigenvalues()).norm(), 1e-14 * scale) << N;
  }
}

TEST(SymmetricEigen, RebuildsTheMatrixWithOrthonormalVectorsAndEigensEigenvalues) {
  expect_decompositions<2>(1);
  expect_decompositions<3>(2);
  expect_decompositions<4>(3);
  expect_decompositions<5>(4);
  expect_decompositions<6>(6);
  expect_decompositions<9>(9);
}

TEST(SymmetricEigen, ReadsOnlyTheLowerTriangle) {
  Eigen::Matrix<double, 5, 5> A = test_matrices<5>(5).front(), B = A;
  B.triangularView<Eigen::StrictlyUpper>().setConstant(1e300);
  const SymmetricEigen<5> a = symmetric_eigen<5>(A), b = symmetric_eigen<5>(B);
  EXPECT_EQ(a.values, b.values);
  EXPECT_EQ(a.vectors, b.vectors);
}

}  // namespace
}  // namespace stiffsoft::contact
