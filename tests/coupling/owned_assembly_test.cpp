// Assembly by the owners of the DOF blocks (owned_assembly.hpp) against the serial loop it
// replaces: the same Hessian and gradient, bit for bit, on two threads, whether the Hessian's
// blocks are new (made after the parallel pass), stored from an earlier assembly or part of
// each, whatever order of the blocks cuts the parts, and the same pattern and version as the
// serial assembly's. And the blocks' order in space that cuts them (block_order.hpp).
#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <limits>
#include <numeric>

#include <stiffsoft/coupling/terms/block_order.hpp>
#include <stiffsoft/coupling/terms/owned_assembly.hpp>

using namespace stiffsoft;

namespace {

/// 60 affine bodies and 90 soft nodes, interleaved.
std::vector<DofBlock> blocks() {
  std::vector<DofBlock> out;
  int offset = 0;
  for (int b = 0; b < 150; ++b) {
    const int size = b % 5 < 2 ? 12 : 3;
    out.push_back({offset, size});
    offset += size;
  }
  return out;
}

/// Random stencils of up to four DOF blocks (−1: a fixed body's vertex), mostly between
/// neighbouring blocks as in a pile, some across the whole range; at most 24 DOFs in all, as
/// a contact between two affine bodies (StencilHessian's capacity).
std::vector<std::array<int, 4>> stencils(std::size_t n, const std::vector<DofBlock>& dofs, unsigned seed) {
  const int num_blocks = int(dofs.size());
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> any(0, num_blocks - 1), near(-4, 4), slot(0, 9);
  std::vector<std::array<int, 4>> out(n);
  for (std::array<int, 4>& s : out) {
    const int centre = any(rng);
    int dofs_used = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      const int pick = slot(rng);
      int b = pick == 0 ? -1 : pick == 1 ? any(rng) : std::clamp(centre + near(rng), 0, num_blocks - 1);
      const auto before = s.begin() + std::ptrdiff_t(i);
      const bool seen = std::find(s.begin(), before, b) != before;
      if (b >= 0 && !seen) {
        if (dofs_used + dofs[std::size_t(b)].size > 24) b = -1;
        else dofs_used += dofs[std::size_t(b)].size;
      }
      s[i] = b;
    }
  }
  return out;
}

/// Stencil k's Jᵀ H J laid out as StencilJacobian lays it out (distinct blocks in order of
/// appearance, pairs (t, s) with block t ≤ block s, s outer), each entry a number of (k, entry).
void stencil_blocks(const std::vector<DofBlock>& dofs, const std::array<int, 4>& s, std::size_t k,
                    StencilHessian& out) {
  std::array<int, 4> distinct{};
  int count = 0;
  for (int b : s)
    if (b >= 0 && std::find(distinct.begin(), distinct.begin() + count, b) == distinct.begin() + count)
      distinct[std::size_t(count++)] = b;
  out.count = 0;
  int next = 0;
  for (int j = 0; j < count; ++j)
    for (int i = 0; i < count; ++i) {
      const int bi = distinct[std::size_t(i)], bj = distinct[std::size_t(j)];
      if (bi > bj) continue;
      out.row[std::size_t(out.count)] = bi;
      out.column[std::size_t(out.count)] = bj;
      out.at[std::size_t(out.count)] = next;
      ++out.count;
      for (int e = 0; e < dofs[std::size_t(bi)].size * dofs[std::size_t(bj)].size; ++e)
        out.values[std::size_t(next + e)] = std::sin(0.37 * double(k) + 1.3 * e + bi) / (1.0 + e);
      next += dofs[std::size_t(bi)].size * dofs[std::size_t(bj)].size;
    }
}

/// H after one assembly of `s`, serially (threads = 1) or by owners, after `earlier` was
/// assembled into it (and cleared): its blocks are stored but not part of the matrix.
struct Assembled {
  Eigen::SparseMatrix<double> upper;
  std::vector<std::int64_t> pattern;
  std::uint64_t version;
  Eigen::VectorXd gradient;
};
using Stencils = std::vector<std::array<int, 4>>;
Assembled assemble_here(const Stencils& s, const Stencils& earlier, const std::vector<int>& rank) {
  const std::vector<DofBlock> dofs = blocks();
  const int nb = int(dofs.size());
  BlockHessian H(dofs);
  const auto fill = [&](const std::vector<std::array<int, 4>>& list) {
    assemble_hessian_by_owner(H, nb, rank, list.size(), [&](std::size_t k) { return list[k]; },
                              [&](std::size_t k, StencilHessian& out) {
                                stencil_blocks(dofs, list[k], k, out);
                              });
  };
  fill(earlier);
  H.clear();
  fill(s);
  const int n = dofs.back().offset + dofs.back().size;
  Assembled a{H.upper(), H.pattern(), H.pattern_version(), Eigen::VectorXd::Zero(n)};
  assemble_gradient_by_owner<Eigen::Vector4d>(
      nb, rank, s.size(), [&](std::size_t k) { return s[k]; },
      [&](std::size_t k, Eigen::Vector4d& out) {
        out << std::cos(0.1 * double(k)), 1.0 / (1.0 + double(k)), 0.3, -0.7;
      },
      [&](std::size_t k, const Eigen::Vector4d& out, const BlockOwner& owner) {
        for (int i = 0; i < 4; ++i)
          if (s[k][std::size_t(i)] >= 0 && owner.owns(s[k][std::size_t(i)]))
            a.gradient[dofs[std::size_t(s[k][std::size_t(i)])].offset + i % 3] += out[i];
      });
  return a;
}

/// assemble_here in an arena of `threads` threads, whatever the machine's cores, with the parts
/// cut along `rank` (empty: the blocks' own order).
Assembled assemble(const std::vector<std::array<int, 4>>& s, const std::vector<std::array<int, 4>>& earlier,
                   int threads, const std::vector<int>& rank = {}) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  tbb::task_arena arena(threads);
  return arena.execute([&] {
    EXPECT_EQ(available_threads(), threads);
    return assemble_here(s, earlier, rank);
  });
}

/// The blocks' own order, reversed and shuffled: orders the parts may be cut along.
std::vector<std::vector<int>> block_orders(int num_blocks) {
  std::vector<int> reversed(static_cast<std::size_t>(num_blocks));
  std::iota(reversed.rbegin(), reversed.rend(), 0);
  std::vector<int> shuffled = reversed;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(7));
  return {{}, reversed, shuffled};
}

void expect_same(const Assembled& a, const Assembled& b) {
  ASSERT_EQ(a.upper.nonZeros(), b.upper.nonZeros());
  ASSERT_EQ(a.pattern, b.pattern);
  EXPECT_EQ(a.version, b.version);
  for (Eigen::Index c = 0; c <= a.upper.outerSize(); ++c)
    ASSERT_EQ(a.upper.outerIndexPtr()[c], b.upper.outerIndexPtr()[c]);
  for (Eigen::Index e = 0; e < a.upper.nonZeros(); ++e) {
    ASSERT_EQ(a.upper.innerIndexPtr()[e], b.upper.innerIndexPtr()[e]);
    ASSERT_EQ(a.upper.valuePtr()[e], b.upper.valuePtr()[e]) << "entry " << e;
  }
  EXPECT_EQ((a.gradient - b.gradient).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace

TEST(OwnedAssembly, GivesTheSerialSumsBitForBitOnNewStoredAndMixedBlocks) {
  const std::vector<DofBlock> dofs = blocks();
  const std::vector<std::array<int, 4>> s = stencils(3000, dofs, 1);
  const std::vector<std::array<int, 4>> none, half = stencils(1500, dofs, 2);
  for (const std::vector<int>& rank : block_orders(int(dofs.size())))
    for (const std::vector<std::array<int, 4>>* earlier : {&none, &s, &half}) {
      const Assembled serial = assemble(s, *earlier, 1), parallel = assemble(s, *earlier, 2, rank);
      ASSERT_GT(serial.pattern.size(), 100u);
      expect_same(serial, parallel);
    }
}

TEST(OwnedAssembly, AddsEveryStencilOnceWhateverItsParts) {
  // Every stencil's entries summed by the owners equal the entries added directly to a dense
  // matrix: none is lost where a stencil spans two parts, none added twice.
  const std::vector<DofBlock> dofs = blocks();
  const std::vector<std::array<int, 4>> s = stencils(2000, dofs, 3);
  const Assembled a = assemble(s, {}, 2, block_orders(int(dofs.size())).back());
  const int n = dofs.back().offset + dofs.back().size;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  StencilHessian out;
  for (std::size_t k = 0; k < s.size(); ++k) {
    stencil_blocks(dofs, s[k], k, out);
    for (int m = 0; m < out.count; ++m) {
      const std::size_t i = std::size_t(m);
      const DofBlock &r = dofs[std::size_t(out.row[i])], &c = dofs[std::size_t(out.column[i])];
      const Eigen::Map<const Eigen::MatrixXd> B(out.values.data() + out.at[std::size_t(m)], r.size, c.size);
      if (out.row[std::size_t(m)] == out.column[std::size_t(m)])
        dense.block(r.offset, c.offset, r.size, c.size) += Eigen::MatrixXd(B.triangularView<Eigen::Upper>());
      else
        dense.block(r.offset, c.offset, r.size, c.size) += B;
    }
  }
  EXPECT_LT((Eigen::MatrixXd(a.upper) - dense).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(BlockOrder, RanksTheBlocksAlongTheAxisTheirPositionsSpreadMost) {
  // Three affine bodies and two soft nodes; positions spread 4 m along y, 1 m along x and z.
  Model model;
  for (int size : {12, 3, 12, 3, 12}) model.add_block(size);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.num_dofs);
  const double y[] = {2.0, -2.0, 0.5, 0.5, 1.0};
  for (std::size_t b = 0; b < 5; ++b) {
    const int at = model.blocks[b].offset;
    q.segment<3>(at) << 0.2 * double(b), y[b], 1.0 - 0.2 * double(b);
    if (model.blocks[b].size == 12) q.segment<9>(at + 3) << 9, 9, 9, 9, 9, 9, 9, 9, 9;  // A: not a position
  }
  EXPECT_EQ(blocks_along_widest_axis(model, q), (std::vector<int>{4, 0, 1, 2, 3}));  // tie: block order
  q[model.blocks[1].offset + 1] = std::numeric_limits<double>::quiet_NaN();         // sorts last
  EXPECT_EQ(blocks_along_widest_axis(model, q), (std::vector<int>{3, 4, 0, 1, 2}));
  EXPECT_TRUE(blocks_along_widest_axis(Model{}, Eigen::VectorXd()).empty());
}
