/// Block Cholesky (block_cholesky.hpp): solutions against a dense factorisation for affine-body
/// (12), soft-node (3) and mixed blocks, reuse of the analysis, refusal of an indefinite matrix,
/// the fill its ordering keeps, the same factor bit for bit on one and two threads, a new
/// factorisation that recomputes only the columns a change reaches, and blocks read in place
/// (BlockUpper) factorised as their compressed copy is, and their products summed as Eigen's
/// kernels sum them. The incomplete factorisation IC(0)
/// (Fill::None): no fill, exact where the pattern fills nothing, and behind "block_cg" the
/// same p bit for bit on one and two threads.

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>
#include <stdexcept>

#include <stiffsoft/coupling/linear_solver/block_cholesky.hpp>
#include <stiffsoft/coupling/linear_solver/block_cholesky_solver.hpp>
#include <stiffsoft/coupling/linear_solver/cholmod_solver.hpp>
#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>

namespace stiffsoft {
namespace {

/// A symmetric positive definite matrix over DOF blocks of the given sizes, as its upper
/// triangle: dense diagonal blocks, dense blocks for the given couplings (pairs of blocks),
/// entries in [−1, 1] and a diagonal that dominates its row.
Eigen::SparseMatrix<double> spd_upper(const std::vector<int>& sizes, const std::vector<std::pair<int, int>>& couplings,
                                      unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<int> offsets{0};
  for (int s : sizes) offsets.push_back(offsets.back() + s);
  const int n = offsets.back();
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  const auto fill = [&](int a, int b) {
    for (int r = offsets[a]; r < offsets[a + 1]; ++r)
      for (int c = offsets[b]; c < offsets[b + 1]; ++c)
        if (a != b || r < c) dense(r, c) = dense(c, r) = u(rng);
  };
  for (int b = 0; b < int(sizes.size()); ++b) fill(b, b);
  for (auto [a, b] : couplings) fill(a, b);
  for (int r = 0; r < n; ++r) dense(r, r) = 1 + dense.row(r).cwiseAbs().sum();
  Eigen::SparseMatrix<double> A = dense.triangularView<Eigen::Upper>().toDenseMatrix().sparseView();
  for (int r = 0; r < n; ++r)  // zeros inside a stored block stay stored, as the assembly stores them
    if (A.coeff(r, r) == 0) A.coeffRef(r, r) = 1;
  A.makeCompressed();
  return A;
}

std::vector<std::pair<int, int>> random_couplings(int blocks, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, blocks - 1);
  std::vector<std::pair<int, int>> pairs;
  while (int(pairs.size()) < count) {
    const int a = pick(rng), b = pick(rng);
    if (a != b) pairs.emplace_back(std::min(a, b), std::max(a, b));
  }
  return pairs;
}

Eigen::VectorXd dense_solution(const Eigen::SparseMatrix<double>& upper, const Eigen::VectorXd& b) {
  const Eigen::MatrixXd full = Eigen::MatrixXd(Eigen::SparseMatrix<double>(upper.selfadjointView<Eigen::Upper>()));
  return full.llt().solve(b);
}

TEST(BlockCholesky, SolvesAffineSoftAndMixedBlocksAsADenseFactorisationDoes) {
  std::mt19937 rng(7);
  std::vector<int> mixed;
  for (int b = 0; b < 50; ++b) mixed.push_back(rng() % 3 == 0 ? 12 : 3);
  for (const std::vector<int>& sizes : {std::vector<int>(40, 12), std::vector<int>(60, 3), mixed}) {
    const int blocks = int(sizes.size());
    const Eigen::SparseMatrix<double> A = spd_upper(sizes, random_couplings(blocks, 2 * blocks, blocks), 1);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1, 2);
    BlockCholesky factor;
    factor.analyze(A, sizes);
    ASSERT_TRUE(factor.factorize(A));
    const Eigen::VectorXd expected = dense_solution(A, b);
    EXPECT_LE((factor.solve(b) - expected).norm(), 1e-12 * expected.norm()) << sizes.front();
    EXPECT_GT(factor.flops(), 0);
    EXPECT_LE(factor.nonzeros(), 0.5 * A.rows() * (A.rows() + 1));
  }
}

TEST(BlockCholesky, ReusesItsAnalysisForNewValuesOfThePattern) {
  const std::vector<int> sizes(30, 12);
  const auto couplings = random_couplings(30, 40, 3);
  const Eigen::SparseMatrix<double> A = spd_upper(sizes, couplings, 1), B = spd_upper(sizes, couplings, 2);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
  BlockCholesky factor;
  factor.analyze(A, sizes);
  for (const Eigen::SparseMatrix<double>* M : {&A, &B, &A}) {
    ASSERT_TRUE(factor.factorize(*M));
    const Eigen::VectorXd expected = dense_solution(*M, b);
    EXPECT_LE((factor.solve(b) - expected).norm(), 1e-12 * expected.norm());
  }
}

TEST(BlockCholesky, RefusesAMatrixThatIsNotPositiveDefinite) {
  const std::vector<int> sizes{12, 3, 12, 3};
  Eigen::SparseMatrix<double> A = spd_upper(sizes, {{0, 1}, {1, 2}, {2, 3}}, 4);
  A.coeffRef(20, 20) = -A.coeff(20, 20);  // a negative diagonal entry in the third block
  BlockCholesky factor;
  factor.analyze(A, sizes);
  EXPECT_FALSE(factor.factorize(A));
  BlockCholeskySolver solver;
  solver.set_block_sizes(sizes);
  solver.analyze_pattern(A);
  EXPECT_FALSE(solver.factorize(A));
  EXPECT_EQ(solver.last_report().status, LinearSolveStatus::Indefinite);
  EXPECT_FALSE(solver.solve(Eigen::VectorXd::Ones(A.rows())).allFinite());
}

TEST(BlockCholesky, EliminatesAHubLastSoThatAStarDoesNotFill) {
  // Block 0 coupled to every other: eliminated first it would fill the whole factor; the
  // minimum-degree ordering eliminates it last, so L has the star's blocks and no more.
  const int blocks = 20;
  std::vector<std::pair<int, int>> star;
  for (int b = 1; b < blocks; ++b) star.emplace_back(0, b);
  const Eigen::SparseMatrix<double> A = spd_upper(std::vector<int>(blocks, 12), star, 5);
  BlockCholesky factor;
  factor.analyze(A, std::vector<int>(blocks, 12));
  EXPECT_EQ(factor.nonzeros(), blocks * 78.0 + (blocks - 1) * 144.0);
  ASSERT_TRUE(factor.factorize(A));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), 1, 3);
  const Eigen::VectorXd expected = dense_solution(A, b);
  EXPECT_LE((factor.solve(b) - expected).norm(), 1e-12 * expected.norm());
}

TEST(BlockCholesky, GivesTheSameSolutionBitForBitOnOneAndTwoThreads) {
  // 400 bodies in loose clusters: many independent columns per level of the elimination tree,
  // which the factorisation and the solves split between threads.
  const std::vector<int> sizes(400, 12);
  const Eigen::SparseMatrix<double> A = spd_upper(sizes, random_couplings(400, 300, 6), 6);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -3, 1);
  std::vector<Eigen::VectorXd> x;
  for (int threads : {1, 2}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    BlockCholesky factor;
    factor.analyze(A, sizes);
    ASSERT_TRUE(factor.factorize(A));
    x.push_back(factor.solve(b));
  }
  EXPECT_EQ(x[0], x[1]);
  EXPECT_LE((A.selfadjointView<Eigen::Upper>() * x[0] - b).norm(), 1e-12 * b.norm());
}

TEST(BlockCholesky, FactorisesAgainOnlyTheColumnsAChangeReaches) {
  // 15 separate pairs of bodies: changing body 4's diagonal block reaches its pair only.
  const int blocks = 30;
  const std::vector<int> sizes(blocks, 12);
  std::vector<std::pair<int, int>> pairs;
  for (int b = 0; b < blocks; b += 2) pairs.emplace_back(b, b + 1);
  const Eigen::SparseMatrix<double> A = spd_upper(sizes, pairs, 9);
  Eigen::SparseMatrix<double> B = A;
  for (int r = 48; r < 60; ++r) B.coeffRef(r, r) *= 1.5;  // body 4, still diagonally dominant
  Eigen::SparseMatrix<double> C = B;
  C.coeffRef(50, 50) = -1;  // not positive definite
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1, 1);
  const auto fresh_solution = [&](const Eigen::SparseMatrix<double>& M) {
    BlockCholesky fresh;
    fresh.analyze(M, sizes);
    EXPECT_TRUE(fresh.factorize(M));
    return fresh.solve(b);
  };
  BlockCholesky factor;
  factor.analyze(A, sizes);
  ASSERT_TRUE(factor.factorize(A));
  EXPECT_EQ(factor.refactored_columns(), std::size_t(blocks));
  ASSERT_TRUE(factor.factorize(B));
  EXPECT_GE(factor.refactored_columns(), 1u);
  EXPECT_LE(factor.refactored_columns(), 2u);
  EXPECT_EQ(factor.solve(b), fresh_solution(B));  // bit for bit
  ASSERT_TRUE(factor.factorize(A));
  EXPECT_LE(factor.refactored_columns(), 2u);
  EXPECT_EQ(factor.solve(b), fresh_solution(A));
  EXPECT_FALSE(factor.factorize(C));
  ASSERT_TRUE(factor.factorize(B));  // after a failure every column again
  EXPECT_EQ(factor.refactored_columns(), std::size_t(blocks));
  EXPECT_EQ(factor.solve(b), fresh_solution(B));
}

TEST(BlockCholesky, KeepsItsAnalysisAndFactorForThePatternItAnalysedLast) {
  const int blocks = 30;
  const std::vector<int> sizes(blocks, 12);
  std::vector<std::pair<int, int>> pairs;
  for (int b = 0; b + 1 < blocks; ++b) pairs.emplace_back(b, b + 1);
  const Eigen::SparseMatrix<double> A = spd_upper(sizes, pairs, 9);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1, 1);
  BlockCholesky factor;
  factor.analyze(A, sizes);
  ASSERT_TRUE(factor.factorize(A));
  const Eigen::VectorXd first = factor.solve(b);
  factor.analyze(A, sizes);  // the same pattern: nothing to analyse, the factor stays
  ASSERT_TRUE(factor.factorize(A));
  EXPECT_EQ(factor.refactored_columns(), 0u);
  EXPECT_EQ(factor.solve(b), first);
  // A new pattern is analysed afresh: every column is factorised again.
  std::vector<std::pair<int, int>> more = pairs;
  more.emplace_back(0, blocks - 1);
  const Eigen::SparseMatrix<double> B = spd_upper(sizes, more, 9);
  factor.analyze(B, sizes);
  ASSERT_TRUE(factor.factorize(B));
  EXPECT_EQ(factor.refactored_columns(), std::size_t(blocks));
  BlockCholesky fresh;
  fresh.analyze(B, sizes);
  ASSERT_TRUE(fresh.factorize(B));
  EXPECT_EQ(factor.solve(b), fresh.solve(b));
}

TEST(BlockCholesky, RejectsBlocksThatDoNotCoverTheMatrix) {
  const Eigen::SparseMatrix<double> A = spd_upper({12, 12}, {}, 8);
  BlockCholesky factor;
  EXPECT_THROW(factor.analyze(A, {12, 3}), std::invalid_argument);
}

TEST(BlockCholesky, FactorisesBlocksInPlaceAsItFactorisesTheirCompressedCopy) {
  const std::vector<int> sizes{12, 3, 12, 12, 3, 3, 12, 3};
  const Eigen::SparseMatrix<double> A = spd_upper(sizes, {{0, 1}, {0, 3}, {1, 4}, {2, 6}, {3, 7}, {5, 6}}, 11);
  const GatheredBlocks g = gather_blocks(A, sizes);
  const double shift = 0.75;
  Eigen::SparseMatrix<double> shifted = A;
  for (int r = 0; r < A.rows(); ++r) shifted.coeffRef(r, r) += shift;
  EXPECT_EQ(Eigen::MatrixXd(g.blocks.compressed()), Eigen::MatrixXd(A));
  EXPECT_EQ(Eigen::MatrixXd(g.blocks.compressed(shift)), Eigen::MatrixXd(shifted));
  EXPECT_EQ(g.blocks.upper_nonzeros(), long(A.nonZeros()));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -2, 1);
  const Eigen::VectorXd Ab = A.selfadjointView<Eigen::Upper>() * b;
  EXPECT_LE((g.blocks.multiply(b) - Ab).norm(), 1e-14 * Ab.norm());

  BlockCholesky from_csc, from_blocks;
  from_csc.analyze(shifted, sizes);
  ASSERT_TRUE(from_csc.factorize(shifted));
  from_blocks.analyze(g.blocks);
  ASSERT_TRUE(from_blocks.factorize(g.blocks));
  ASSERT_TRUE(from_blocks.factorize(g.blocks, shift));  // a new shift: every column again
  EXPECT_EQ(from_blocks.refactored_columns(), sizes.size());
  EXPECT_EQ(from_blocks.solve(b), from_csc.solve(b));  // bit for bit
  const Eigen::VectorXd shifted_b = shifted.selfadjointView<Eigen::Upper>() * b;
  EXPECT_LE((from_blocks.multiply(b) - shifted_b).norm(), 1e-14 * shifted_b.norm());

  // Behind the LinearSolver interface: the block backend reads the blocks, CHOLMOD their copy.
  BlockCholeskySolver block_solver, csc_solver;
  block_solver.analyze_blocks(g.blocks);
  ASSERT_TRUE(block_solver.factorize_blocks(g.blocks, shift));
  csc_solver.set_block_sizes(sizes);
  csc_solver.analyze_pattern(shifted);
  ASSERT_TRUE(csc_solver.factorize(shifted));
  EXPECT_EQ(block_solver.solve(b), csc_solver.solve(b));
  CholmodSolver cholmod_blocks, cholmod_csc;
  cholmod_blocks.analyze_blocks(g.blocks);
  ASSERT_TRUE(cholmod_blocks.factorize_blocks(g.blocks, shift));
  cholmod_csc.analyze_pattern(shifted);
  ASSERT_TRUE(cholmod_csc.factorize(shifted));
  EXPECT_EQ(cholmod_blocks.solve(b), cholmod_csc.solve(b));

  // Blocks of another pattern, or below the diagonal, are refused.
  const GatheredBlocks other = gather_blocks(spd_upper(sizes, {{0, 2}}, 12), sizes);
  EXPECT_THROW(from_blocks.factorize(other.blocks), std::invalid_argument);
  BlockUpper below = g.blocks;
  below.rows[0] = 1;  // column 0 claims block row 1
  BlockCholesky refuses;
  EXPECT_THROW(refuses.analyze(below), std::invalid_argument);
}

TEST(BlockUpper, MultipliesAffineBlocksAsEigensProductsDoBitForBit) {
  // multiply() forms the 12×12 off-diagonal blocks' products in its own loops, summed in the
  // order of Eigen's matrix–vector kernels: the same y as those products, block by block in
  // multiply()'s order (a block of y: its column's blocks, then its row's in later columns).
  const std::vector<int> sizes{3, 12, 12, 12, 3, 12, 12};  // odd and even offsets
  const Eigen::SparseMatrix<double> A =
      spd_upper(sizes, {{0, 1}, {1, 2}, {1, 3}, {2, 5}, {3, 4}, {3, 6}, {5, 6}, {2, 6}}, 17);
  const GatheredBlocks g = gather_blocks(A, sizes);
  const BlockUpper& H = g.blocks;
  Eigen::VectorXd x(A.rows());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = std::sin(1.7 * double(i) + 0.3);
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(x.size());
  const auto block = [&](int k) {
    const int i = H.rows[std::size_t(k)];
    int j = 0;
    while (H.column_starts[std::size_t(j) + 1] <= k) ++j;
    return std::make_pair(i, j);
  };
  const auto A_of = [&](int k, int i, int j) { return Eigen::Map<const Eigen::MatrixXd>(H.values[std::size_t(k)], H.size(i), H.size(j)); };
  for (int m = 0; m < H.num_blocks(); ++m) {
    auto y = expected.segment(H.offsets[std::size_t(m)], H.size(m));
    for (int k = H.column_starts[std::size_t(m)]; k < H.column_starts[std::size_t(m) + 1]; ++k) {
      const auto [i, j] = block(k);
      if (i == j)
        y.noalias() += A_of(k, i, j).selfadjointView<Eigen::Upper>() * x.segment(H.offsets[std::size_t(j)], H.size(j));
      else if (H.size(i) == 12 && H.size(j) == 12)
        y.noalias() += Eigen::Matrix<double, 12, 12>(A_of(k, i, j)).transpose() * x.segment<12>(H.offsets[std::size_t(i)]);
      else
        y.noalias() += A_of(k, i, j).transpose() * x.segment(H.offsets[std::size_t(i)], H.size(i));
    }
    for (int k = 0; k < int(H.rows.size()); ++k) {
      const auto [i, j] = block(k);
      if (i != m || j == m) continue;
      if (H.size(i) == 12 && H.size(j) == 12)
        y.noalias() += Eigen::Matrix<double, 12, 12>(A_of(k, i, j)) * x.segment<12>(H.offsets[std::size_t(j)]);
      else
        y.noalias() += A_of(k, i, j) * x.segment(H.offsets[std::size_t(j)], H.size(j));
    }
  }
  EXPECT_EQ(H.multiply(x), expected);
}

TEST(IncompleteBlockCholesky, KeepsOnlyTheBlocksOfHAndIsExactWhereTheyFillNothing) {
  // The star of EliminatesAHubLast…, in the blocks' own order: the hub comes first, so the exact
  // factor would fill every block; IC(0) keeps the star's blocks.
  const int blocks = 20;
  std::vector<std::pair<int, int>> star, chain;
  for (int b = 1; b < blocks; ++b) star.emplace_back(0, b), chain.emplace_back(b - 1, b);
  const std::vector<int> sizes(blocks, 12);
  BlockCholesky incomplete(BlockCholesky::Fill::None);
  incomplete.analyze(spd_upper(sizes, star, 5), sizes);
  EXPECT_EQ(incomplete.nonzeros(), blocks * 78.0 + (blocks - 1) * 144.0);
  // A chain in its own order fills nothing: IC(0) is the exact factor.
  const Eigen::SparseMatrix<double> A = spd_upper(sizes, chain, 6);
  incomplete.analyze(A, sizes);
  ASSERT_TRUE(incomplete.factorize(A));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1, 2);
  const Eigen::VectorXd expected = dense_solution(A, b);
  EXPECT_LE((incomplete.solve(b) - expected).norm(), 1e-12 * expected.norm());
}

TEST(IncompleteBlockCholesky, PreconditionsConjugateGradientsToTheSamePOnOneAndTwoThreads) {
  // 400 bodies with 300 random couplings: IC(0) drops fill, so CG iterates; its levels of
  // independent columns are split between threads.
  const std::vector<int> sizes(400, 12);
  const Eigen::SparseMatrix<double> A = spd_upper(sizes, random_couplings(400, 300, 6), 6);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -3, 1);
  std::vector<Eigen::VectorXd> p;
  for (int threads : {1, 2}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const std::unique_ptr<LinearSolver> solver = make_linear_solver("block_cg");
    EXPECT_TRUE(solver->is_iterative());
    solver->set_block_sizes(sizes);
    solver->set_relative_tolerance(1e-10);
    solver->analyze_pattern(A);
    ASSERT_TRUE(solver->factorize(A));
    p.push_back(solver->solve(b));
    const LinearSolveReport& r = solver->last_report();
    EXPECT_TRUE(r.converged()) << r.reason;
    EXPECT_GT(r.iterations, 1);
    EXPECT_LE(r.relative_residual, 1e-10);
  }
  EXPECT_EQ(p[0], p[1]);
  EXPECT_LE((A.selfadjointView<Eigen::Upper>() * p[0] - b).norm(), 1e-10 * b.norm());
}

}  // namespace
}  // namespace stiffsoft
