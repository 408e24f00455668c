// BlockHessian: the assembled matrix against a dense reference, and its reuse across clear():
// blocks not added again leave the matrix and its pattern, and the pattern's version says
// whether the pattern changed.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include <stiffsoft/coupling/model/block_hessian.hpp>

using namespace stiffsoft;

namespace {

/// One affine block (12) between two soft nodes (3): offsets 0, 3, 15.
const std::vector<DofBlock> kBlocks{{0, 3}, {3, 12}, {15, 3}};

Eigen::MatrixXd dense(const BlockHessian& H) {
  return Eigen::MatrixXd(Eigen::SparseMatrix<double>(H.upper().selfadjointView<Eigen::Upper>()));
}

/// Adds a random block at (i, j) to H and to the dense reference D (both triangles).
void add_random(BlockHessian& H, Eigen::MatrixXd& D, int i, int j, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd B(kBlocks[i].size, kBlocks[j].size);
  for (Eigen::Index k = 0; k < B.size(); ++k) B.data()[k] = u(rng);
  if (i == j) B = (B + B.transpose()).eval();
  H.add(i, j, B);
  D.block(kBlocks[i].offset, kBlocks[j].offset, B.rows(), B.cols()) += B;
  if (i != j) D.block(kBlocks[j].offset, kBlocks[i].offset, B.cols(), B.rows()) += B.transpose();
}

}  // namespace

TEST(BlockHessian, AssemblesTheSymmetricMatrixOfItsBlocks) {
  std::mt19937 rng(1);
  BlockHessian H(kBlocks);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(18, 18);
  add_random(H, D, 0, 0, rng);
  add_random(H, D, 1, 1, rng);
  add_random(H, D, 0, 1, rng);
  add_random(H, D, 2, 1, rng);  // below the diagonal: stored transposed
  add_random(H, D, 1, 2, rng);  // the same block again: added
  EXPECT_LT((dense(H) - D).norm(), 1e-14);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(18, -1, 2);
  EXPECT_LT((H.multiply(x) - D * x).norm(), 1e-13);
  EXPECT_EQ(H.pattern(), (std::vector<std::int64_t>{0 * 3 + 1, 1 * 3 + 2}));
}

TEST(BlockHessian, ClearStartsAFreshMatrixAndKeepsTheVersionOfARepeatedPattern) {
  std::mt19937 rng(2);
  BlockHessian H(kBlocks);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(18, 18);
  add_random(H, D, 0, 1, rng);
  add_random(H, D, 1, 2, rng);
  const std::uint64_t first = H.pattern_version();

  H.clear();  // the same pattern again, new values
  D.setZero();
  add_random(H, D, 1, 2, rng);
  add_random(H, D, 0, 1, rng);
  EXPECT_LT((dense(H) - D).norm(), 1e-14);
  EXPECT_EQ(H.pattern_version(), first);

  H.clear();  // a sub-pattern: the dropped block is gone from matrix and pattern
  D.setZero();
  add_random(H, D, 0, 1, rng);
  EXPECT_LT((dense(H) - D).norm(), 1e-14);
  EXPECT_EQ(H.pattern(), (std::vector<std::int64_t>{1}));
  const std::uint64_t smaller = H.pattern_version();
  EXPECT_NE(smaller, first);

  add_random(H, D, 0, 2, rng);  // grows within one assembly: a new version at once
  EXPECT_NE(H.pattern_version(), smaller);
  EXPECT_NE(H.pattern_version(), first);
  EXPECT_LT((dense(H) - D).norm(), 1e-14);
}

TEST(BlockHessian, DecoupleZeroesTheOffDiagonalBlocksOfHeldBlocks) {
  std::mt19937 rng(3);
  BlockHessian H(kBlocks);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(18, 18);
  add_random(H, D, 0, 1, rng);
  add_random(H, D, 1, 2, rng);
  add_random(H, D, 2, 2, rng);
  H.decouple({0, 0, 1});
  D.block(3, 15, 12, 3).setZero();
  D.block(15, 3, 3, 12).setZero();
  EXPECT_LT((dense(H) - D).norm(), 1e-14);
}

TEST(BlockHessian, DropsTheStorageOfBlocksLongUnusedAndKeepsTheMatrixAndItsVersion) {
  // 200 soft nodes; 10,000 couplings once (a pile's bodies that later parted), then ten.
  std::vector<DofBlock> nodes;
  for (int b = 0; b < 200; ++b) nodes.push_back({3 * b, 3});
  BlockHessian H(nodes);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> any(0, 199);
  const Eigen::Matrix3d B = Eigen::Matrix3d::Identity();
  while (H.stored_blocks() < 10000) {
    const int i = any(rng), j = any(rng);
    if (i != j) H.add(i, j, B);
  }
  const auto assemble_ten = [&] {
    H.clear();
    for (int k = 0; k < 10; ++k) H.add(k, 100 + k, double(k + 1) * B);
  };
  assemble_ten();
  EXPECT_GE(H.stored_blocks(), 10000u);  // kept while they may come back
  const std::uint64_t version = H.pattern_version();
  assemble_ten();                        // the clear before it drops the 9,990 others
  EXPECT_EQ(H.stored_blocks(), 10u);
  EXPECT_EQ(H.pattern_version(), version);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(600, 600);
  for (int k = 0; k < 10; ++k) D.block(3 * k, 3 * (100 + k), 3, 3) = double(k + 1) * B;
  EXPECT_EQ(Eigen::MatrixXd(H.upper().triangularView<Eigen::StrictlyUpper>()), D);
  H.add(5, 7, B);  // a new coupling after the drop: stored again
  EXPECT_EQ(H.stored_blocks(), 11u);
}
