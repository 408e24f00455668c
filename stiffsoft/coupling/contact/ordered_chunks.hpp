#pragma once
/// @file Parallel loops whose outputs are gathered in a fixed order: items are cut into chunks
/// of a fixed size, each chunk fills its own part in parallel, and the parts are then merged
/// serially in chunk order. The merged result is what the serial loop would give, whatever the
/// thread count and schedule, without sorting it afterwards.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace stiffsoft {

/// For i in [0, n): fill(i, part) adds item i's output to its chunk's `part` (a default-
/// constructed Part per chunk of `grain` items, filled in increasing i); merge(part) then
/// receives the parts in chunk order, on the calling thread.
template <class Part, class Fill, class Merge>
void in_ordered_chunks(std::size_t n, std::size_t grain, const Fill& fill, const Merge& merge) {
  const std::size_t chunks = (n + grain - 1) / grain;
  std::vector<Part> parts(chunks);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    const std::size_t end = std::min(n, (c + 1) * grain);
    for (std::size_t i = c * grain; i < end; ++i) fill(i, parts[c]);
  });
  for (Part& part : parts) merge(part);
}

}  // namespace stiffsoft
