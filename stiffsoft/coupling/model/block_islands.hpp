#pragma once
/// @file Islands of DOF blocks for one Newton move: blocks joined (union–find) whenever some
/// energy term couples them on that move. Blocks in different islands share no stencil of any
/// term, so the energy is a sum over islands, the projected Hessian is block-diagonal over them
/// and each island's part of the Newton direction is a descent direction of its own: each island
/// may take its own step length (docs/newton.md, "Each island its own step").

#include <array>
#include <vector>

#include <Eigen/Core>

namespace stiffsoft {

struct Model;

/// Union–find over the DOF blocks of a model, then numbered islands.
class BlockIslands {
 public:
  /// Every one of `blocks` DOF blocks its own island.
  explicit BlockIslands(int blocks);
  /// Joins the islands of blocks a and b; a block index < 0 (no DOFs) is ignored.
  void join(int a, int b);
  /// Joins the blocks of a stencil's (up to four) vertices; entries < 0 are ignored.
  void join_blocks(const std::array<int, 4>& blocks);
  /// Joins every block into one island.
  void join_all();
  /// Numbers the islands 0 … count() − 1 (in the order of their first block; one island when
  /// there is no block); call after the last join and before island().
  void number();
  /// Number of islands (after number()).
  int count() const { return m_count; }
  /// Island of block b (after number()).
  int island(int b) const { return m_island[std::size_t(b)]; }
  /// dq with each block's DOFs multiplied by its island's entry of `scale` (after number()).
  Eigen::VectorXd scaled(const Model& model, const Eigen::VectorXd& dq, const std::vector<double>& scale) const;

 private:
  int root(int b);

  std::vector<int> m_parent;
  std::vector<int> m_island;
  int m_count = 0;
  bool m_all = false;
};

/// The DOF block that moves surface vertex v (−1: none, a fixed body's or node's vertex).
int vertex_block(const Model& model, int v);
/// vertex_block of every surface vertex, |V|.
std::vector<int> vertex_blocks(const Model& model);

}  // namespace stiffsoft
