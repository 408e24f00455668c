#pragma once
/// @file Sums of many independent terms (one per body, node or stencil), computed in parallel
/// and added in index order on the calling thread: the sum the serial loop gives, bit for bit,
/// whatever the thread count.

#include <cstddef>
#include <vector>

#include <stiffsoft/coupling/for_each_item.hpp>

namespace stiffsoft {

/// start + term(0) + term(1) + … + term(n − 1), added left to right; the terms are computed in
/// parallel tasks of at least `grain` of them.
template <class Term>
double ordered_sum(double start, std::size_t n, std::size_t grain, const Term& term) {
  std::vector<double> terms(n);
  for_each_item(n, grain, [&](std::size_t k) { terms[k] = term(k); });
  double sum = start;
  for (const double t : terms) sum += t;
  return sum;
}

}  // namespace stiffsoft
