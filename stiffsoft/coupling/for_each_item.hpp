#pragma once
/// @file A parallel loop over independent items (bodies, nodes, stencils, blocks), each writing
/// only what it owns, so that the result does not depend on the threads.

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>

namespace stiffsoft {

/// The threads a parallel loop started here may use: the arena's, bounded by any
/// tbb::global_control (`--threads`).
inline int available_threads() {
  const std::size_t limit = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return int(std::min(std::size_t(tbb::this_task_arena::max_concurrency()), limit));
}

/// f(k) for k in [0, n) in parallel tasks of at least `grain` items; f(k) must write only what
/// item k owns (its body's rows or segment, its diagonal block of H, its place in a pool).
template <class F>
void for_each_item(std::size_t n, std::size_t grain, const F& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k < r.end(); ++k) f(k);
  });
}

}  // namespace stiffsoft
