#pragma once
/// @file Assembly item by item (contact stencil, tetrahedron, affine body) in chunks: local
/// gradients or Hessians computed in parallel into a small buffer, then added to the global
/// vector or matrix serially in item order, chunk after chunk. The sums are the same whatever
/// the thread count (the order of addition is fixed), and the buffer stays small: one 12×12
/// Hessian per item for thousands of contacts or elements would be megabytes of freshly mapped
/// memory every Newton iteration.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace stiffsoft {

/// For k in [0, n): compute(k, out) fills `out` (a Local) in parallel; add(k, out) then adds it
/// to the global quantity, serially and in increasing k.
template <class Local, class Compute, class Add>
void assemble_in_chunks(std::size_t n, const Compute& compute, const Add& add) {
  constexpr std::size_t kChunk = 128;  // 128 12×12 Hessians: 144 KiB; 128 StencilHessians: 450 KiB
  std::vector<Local> local(std::min(n, kChunk));
  for (std::size_t begin = 0; begin < n; begin += kChunk) {
    const std::size_t end = std::min(n, begin + kChunk);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, 16), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k < r.end(); ++k) compute(k, local[k - begin]);
    });
    for (std::size_t k = begin; k < end; ++k) add(k, local[k - begin]);
  }
}

}  // namespace stiffsoft
