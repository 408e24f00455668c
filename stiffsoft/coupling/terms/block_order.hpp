#pragma once
/// @file The DOF blocks in an order of space, for cutting them into parts that few stencils span
/// (owned_assembly.hpp). A pile's bodies are numbered as they were placed, not where they came
/// to rest: halves of their numbers split 29 % of full's resting contacts between two threads,
/// each such stencil computed by both (docs/benchmarks.md, session 58).

#include <Eigen/Core>
#include <vector>

#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// Each DOF block's rank along the axis on which the blocks' positions spread most, ties in
/// block order: a permutation of 0 … blocks − 1. A block's position is its first three DOFs in
/// q (an affine body's translation, a soft node's position).
std::vector<int> blocks_along_widest_axis(const Model& model, const Eigen::VectorXd& q);

}  // namespace stiffsoft
