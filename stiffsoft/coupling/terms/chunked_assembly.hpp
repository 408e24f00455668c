#pragma once
/// @file Assembly item by item (the soft bodies' tetrahedra) in chunks: local gradients or
/// Hessians computed in parallel into small buffers, then added to the global vector or matrix
/// serially in item order. The sums are the same whatever the thread count (the order of
/// addition is fixed), and the buffers stay small: one 12×12 Hessian per item for thousands of
/// elements would be megabytes of freshly mapped memory every Newton iteration. (Contact and
/// friction stencils are assembled by the owners of their blocks instead: owned_assembly.hpp.)
///
/// The chunks flow through a pipeline: while one thread adds chunk k, the others already
/// compute chunks k + 1, k + 2, …, so the serial addition overlaps the parallel work instead
/// of following it.

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace stiffsoft {

/// For k in [0, n): compute(k, out) fills `out` (a Local) in parallel; add(k, out) then adds it
/// to the global quantity, serially and in increasing k.
template <class Local, class Compute, class Add>
void assemble_in_chunks(std::size_t n, const Compute& compute, const Add& add) {
  constexpr std::size_t kChunk = 32;  // 32 element Hessians
  if (n == 0) return;
  // Chunks in flight at once; chunk c uses buffer c mod tokens. The last stage finishes the
  // chunks in order, so chunk c + tokens enters only after chunk c has left its buffer.
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  const std::size_t tokens = std::min(chunks, std::size_t(2 * tbb::this_task_arena::max_concurrency()));
  // Buffers of default-initialised entries: value-initialising an aggregate Local zeroes it
  // (37 KiB per buffer and call for the elements' Hessians), and copying one buffer into the
  // others cost 3 % of a Newton iteration on medium; compute() fills every entry it reads.
  struct Entry {
    Local value;
    Entry() {}
  };
  std::vector<std::vector<Entry>> buffers(tokens);
  for (std::vector<Entry>& buffer : buffers) buffer.resize(std::min(n, kChunk));
  std::size_t next = 0;
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                          [&](tbb::flow_control& fc) -> std::size_t {
                                            if (next == chunks) fc.stop();
                                            return next++;
                                          }) &
          tbb::make_filter<std::size_t, std::size_t>(tbb::filter_mode::parallel,
                                                     [&](std::size_t c) {
                                                       std::vector<Entry>& local = buffers[c % tokens];
                                                       const std::size_t begin = c * kChunk;
                                                       const std::size_t end = std::min(n, begin + kChunk);
                                                       for (std::size_t k = begin; k < end; ++k) compute(k, local[k - begin].value);
                                                       return c;
                                                     }) &
          tbb::make_filter<std::size_t, void>(tbb::filter_mode::serial_in_order, [&](std::size_t c) {
            const std::vector<Entry>& local = buffers[c % tokens];
            const std::size_t begin = c * kChunk;
            const std::size_t end = std::min(n, begin + kChunk);
            for (std::size_t k = begin; k < end; ++k) add(k, local[k - begin].value);
          }));
}

}  // namespace stiffsoft
