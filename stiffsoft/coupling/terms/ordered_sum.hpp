#pragma once
/// @file Sums of many independent terms (one per body, node or stencil), computed in parallel
/// and added in index order on the calling thread: the sum the serial loop gives, bit for bit,
/// whatever the thread count.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>
#include <vector>

namespace stiffsoft {

/// start + term(0) + term(1) + … + term(n − 1), added left to right; the terms are computed in
/// parallel tasks of at least `grain` of them.
template <class Term>
double ordered_sum(double start, std::size_t n, std::size_t grain, const Term& term) {
  std::vector<double> terms(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k < r.end(); ++k) terms[k] = term(k);
  });
  double sum = start;
  for (const double t : terms) sum += t;
  return sum;
}

/// f(k) for k in [0, n) in parallel tasks of at least `grain`; f(k) must write only what item k
/// owns (its body's segment of a gradient, its diagonal block of H).
template <class F>
void for_each_item(std::size_t n, std::size_t grain, const F& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k < r.end(); ++k) f(k);
  });
}

}  // namespace stiffsoft
