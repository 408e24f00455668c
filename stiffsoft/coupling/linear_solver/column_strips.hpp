#pragma once
/// @file The three strips of four columns of a 12×12 block (an affine body's DOFs), for the
/// kernels that work on one triangle of it: each strip is a fixed-size block, so Eigen
/// vectorises it, and the strips reach down to or over from the diagonal only.

namespace stiffsoft {

/// Calls strip.template operator()<C>() for C = 0, 1, 2: the strip of columns 4C … 4C + 3.
template <class Strip>
void for_column_strips(const Strip& strip) {
  strip.template operator()<0>();
  strip.template operator()<1>();
  strip.template operator()<2>();
}

}  // namespace stiffsoft
