#pragma once
/// @file Assembly of contact and friction stencils by the owners of the DOF blocks: the blocks
/// are cut into parts (consecutive in space, block_order.hpp), and one task per part goes
/// through the stencils in increasing order, computing each one that touches one of its blocks
/// and adding what falls in them (a gradient's segments; the Hessian's blocks by their row).
/// Every entry so receives its stencils' terms in stencil order, as a serial loop adds them:
/// the sums depend neither on the thread count nor on the cut. A stencil spanning two parts is
/// computed in both, and no thread reads what another computed (chunked_assembly.hpp's serial
/// addition does, which took this machine 1.8× its one-thread time: docs/benchmarks.md,
/// session 57).

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <stiffsoft/coupling/for_each_item.hpp>
#include <stiffsoft/coupling/model/block_hessian.hpp>
#include <stiffsoft/coupling/model/stencil_jacobian.hpp>

namespace stiffsoft {

/// The parts of one assembly over n stencils: one per thread of the arena (one, a serial
/// assembly, with one thread or few stencils), cut between consecutive DOF blocks of the order
/// `rank` gives (rank[b]: block b's place; empty: the blocks' own order) where about equally
/// many stencils have their last block below. blocks(k) gives stencil k's DOF blocks (an
/// iterable of ints, −1 for none). Any cut gives the same sums; one that few stencils span
/// (block_order.hpp) gives each thread less to compute twice.
class BlockParts {
 public:
  /// The parts for n stencils over num_blocks DOF blocks.
  template <class Blocks>
  BlockParts(int num_blocks, std::size_t n, const Blocks& blocks, const std::vector<int>& rank = {})
      : m_n(n) {
    constexpr std::size_t kSerialBelow = 256;  // stencils
    constexpr std::size_t kSample = 8;         // every kSample-th stencil counted for the cut
    m_parts = n < kSerialBelow ? 1 : std::min(32, available_threads());
    if (m_parts == 1) return;
    const auto place = [&](int b) { return rank.empty() ? b : rank[std::size_t(b)]; };
    std::vector<std::int64_t> per_place(static_cast<std::size_t>(num_blocks), 0);
    std::int64_t counted = 0;
    for (std::size_t k = 0; k < n; k += kSample) {
      int last = -1;
      for (int b : blocks(k))
        if (b >= 0) last = std::max(last, place(b));
      if (last >= 0) ++per_place[std::size_t(last)], ++counted;
    }
    std::vector<int> part_of_place(static_cast<std::size_t>(num_blocks));
    std::int64_t seen = 0;
    for (int r = 0, part = 0; r < num_blocks; ++r) {
      part_of_place[std::size_t(r)] = part;
      seen += per_place[std::size_t(r)];
      if (part + 1 < m_parts && seen * m_parts >= (part + 1) * counted) ++part;
    }
    m_part_of.resize(static_cast<std::size_t>(num_blocks));
    for (int b = 0; b < num_blocks; ++b) m_part_of[std::size_t(b)] = part_of_place[std::size_t(place(b))];
    m_mask.resize(n);
    for_each_item(n, 1024, [&](std::size_t k) {
      std::uint32_t m = 0;
      for (int b : blocks(k))
        if (b >= 0) m |= 1u << m_part_of[std::size_t(b)];
      m_mask[k] = m;
    });
  }
  /// Whether one task does it all, in stencil order.
  bool serial() const { return m_parts == 1; }
  /// Number of parts.
  int count() const { return m_parts; }
  /// Part p's blocks as a BlockOwner (StencilJacobian::scatter_gradient).
  BlockOwner owner(int p) const { return m_parts == 1 ? BlockOwner{} : BlockOwner{&m_part_of, p}; }
  /// f(p, k) for every part p in parallel, and in it for every stencil k touching p's blocks,
  /// in increasing k.
  template <class F>
  void run(const F& f) const {
    if (m_parts == 1) {
      for (std::size_t k = 0; k < m_n; ++k) f(0, k);
      return;
    }
    tbb::parallel_for(0, m_parts, [&](int p) {
      const std::uint32_t bit = 1u << p;
      for (std::size_t k = 0; k < m_n; ++k)
        if (m_mask[k] & bit) f(p, k);
    });
  }

 private:
  std::size_t m_n;
  int m_parts = 1;
  std::vector<int> m_part_of;         // the part of each DOF block
  std::vector<std::uint32_t> m_mask;  // the parts each stencil touches, one bit each
};

/// The items k in [0, n) for which pred(k) holds, in increasing order; pred runs in parallel
/// and may write only what item k owns.
template <class Pred>
std::vector<std::size_t> selected_items(std::size_t n, const Pred& pred) {
  constexpr std::size_t kGrain = 1024;
  std::vector<char> selected(n);
  for_each_item(n, kGrain, [&](std::size_t k) { selected[k] = pred(k) ? 1 : 0; });
  std::vector<std::size_t> items;
  for (std::size_t k = 0; k < n; ++k)
    if (selected[k]) items.push_back(k);
  return items;
}

/// Adds Σ_k Jₖᵀ gₖ to g: compute(k, out) makes stencil k's 12-vector, scatter(k, out, owner)
/// adds it to the segments of the blocks `owner` owns. The parts follow the blocks' `rank`
/// (BlockParts).
template <class Local, class Blocks, class Compute, class Scatter>
void assemble_gradient_by_owner(int num_blocks, const std::vector<int>& rank, std::size_t n,
                                const Blocks& blocks, const Compute& compute, const Scatter& scatter) {
  const BlockParts parts(num_blocks, n, blocks, rank);
  parts.run([&](int p, std::size_t k) {
    Local out;
    compute(k, out);
    scatter(k, out, parts.owner(p));
  });
}

/// Adds Σ_k Jₖᵀ Hₖ Jₖ to H: compute(k, out) makes stencil k's blocks. A block with no storage
/// in H yet (its pair of DOF blocks never coupled before in the run) is made afterwards, in
/// stencil order, and then gets its stencils' terms, in stencil order. The parts follow the
/// blocks' `rank` (BlockParts).
template <class Blocks, class Compute>
void assemble_hessian_by_owner(BlockHessian& H, int num_blocks, const std::vector<int>& rank, std::size_t n,
                               const Blocks& blocks, const Compute& compute) {
  const BlockParts parts(num_blocks, n, blocks, rank);
  if (parts.serial()) {
    StencilHessian out;
    for (std::size_t k = 0; k < n; ++k) {
      compute(k, out);
      out.add_to(H);
    }
    return;
  }
  std::vector<std::vector<std::size_t>> unstored(std::size_t(parts.count()));  // per part
  parts.run([&](int p, std::size_t k) {
    StencilHessian out;
    compute(k, out);
    const BlockOwner owner = parts.owner(p);
    bool stored = true;
    for (int m = 0; m < out.count; ++m)
      if (owner.owns(out.row[m]))
        stored = H.add_upper_stored(out.row[m], out.column[m], out.values.data() + out.at[m]) && stored;
    if (!stored) unstored[std::size_t(p)].push_back(k);
  });
  std::vector<std::size_t> late;
  for (const std::vector<std::size_t>& u : unstored) late.insert(late.end(), u.begin(), u.end());
  std::sort(late.begin(), late.end());
  late.erase(std::unique(late.begin(), late.end()), late.end());
  // Every stencil on a block without storage is late: the block's first is where a serial
  // assembly would have made it.
  std::vector<std::pair<int, int>> made;
  StencilHessian out;
  for (std::size_t k : late) {
    compute(k, out);
    for (int m = 0; m < out.count; ++m) {
      const std::pair<int, int> block(out.row[m], out.column[m]);
      if (block.first == block.second) continue;
      const bool is_new = std::find(made.begin(), made.end(), block) != made.end();
      if (!is_new && H.stored(block.first, block.second)) continue;  // added above
      if (!is_new) made.push_back(block);
      H.add_upper(block.first, block.second, out.values.data() + out.at[m]);
    }
  }
}

}  // namespace stiffsoft
