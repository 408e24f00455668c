#pragma once
/// @file How a contact stencil's surface points depend on the DOFs: x_stencil = Σ_s J_s q_s
/// over the DOF blocks of its vertices (at most four): J_s stacks J(x̄) (3×12) for the vertices
/// of an affine body and the identity (3×3) for a soft node. Fixed bodies and nodes carry no
/// DOFs and drop out.
///
/// J is never formed: a vertex's row block is w ⊗ I₃ up to the order of q's entries, with
/// w = (1, x̄₁, x̄₂, x̄₃) on an affine body (x_i = p_i + Σ_k x̄_k A_ik) and w = (1) on a soft
/// node, so Jᵀ H J is a sum of 3×3 blocks of H scaled by products of weights.

#include <Eigen/Core>
#include <array>
#include <vector>

#include <stiffsoft/coupling/model/block_hessian.hpp>
#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// The DOF blocks one task of an assembly adds to (owned_assembly.hpp): those `part_of` puts
/// in part `part`, or every block where `part_of` is null.
struct BlockOwner {
  const std::vector<int>* part_of = nullptr;  ///< the part of each DOF block
  int part = 0;                               ///< the task's part
  /// Whether the task adds to block b.
  bool owns(int b) const { return !part_of || (*part_of)[std::size_t(b)] == part; }
};

/// Jᵀ H_x J of one stencil, split into the dense blocks it adds to the global Hessian: made
/// where the stencil's Hessian is (in parallel, owned_assembly.hpp) and
/// added in stencil order. Of a diagonal block (row = column) only the upper triangle counts,
/// as in BlockHessian.
struct StencilHessian {
  /// Entries of the largest case: a stencil spans at most two affine bodies, whose blocks
  /// (1,1), (1,2), (2,2) are 12×12 each.
  static constexpr int kCapacity = 3 * 144;
  int count = 0;                      ///< number of blocks
  std::array<int, 10> row{}, column{};  ///< global block indices, row ≤ column
  std::array<int, 10> at{};            ///< first entry of each block in `values` (column-major)
  std::array<double, kCapacity> values;  ///< uninitialised until filled
  StencilHessian() {}  // leaves `values` uninitialised: a chunk of them is scratch space
  /// Adds every block to H.
  void add_to(BlockHessian& H) const;
};

/// The linear map from the DOF blocks of a stencil's vertices to its packed vertex positions.
struct StencilJacobian {
  std::array<int, 4> block{-1, -1, -1, -1};   ///< DOF block of each slot
  std::array<int, 4> offset{-1, -1, -1, -1};  ///< first DOF of each slot in q
  std::array<int, 4> columns{0, 0, 0, 0};     ///< DOFs of each slot's block (12 affine, 3 soft node)
  int slots = 0;                              ///< number of slots with DOFs
  std::array<int, 4> slot_of{-1, -1, -1, -1};  ///< slot of each stencil vertex, −1 without DOFs
  std::array<Eigen::Vector4d, 4> w;           ///< weights of each stencil vertex: (1, x̄) or (1, 0, 0, 0)

  /// Builds the map for the given stencil vertices (−1 entries unused).
  StencilJacobian(const Model& model, const std::array<int, 4>& vertices);

  /// J dq: the stencil's packed vertex displacement under the DOF step dq.
  Eigen::Matrix<double, 12, 1> step(const Eigen::VectorXd& dq) const;
  /// Adds Jᵀ g_x to the global gradient g, in the segments of the blocks `owner` owns.
  void scatter_gradient(const Eigen::Matrix<double, 12, 1>& g_x, Eigen::VectorXd& g,
                        const BlockOwner& owner = {}) const;
  /// Jᵀ H_x J by pairs of DOF blocks, into `out`.
  void block_hessians(const Eigen::Matrix<double, 12, 12>& H_x, StencilHessian& out) const;
  /// Jᵀ (Bᵀ C B) J by pairs of DOF blocks, into `out`, for a Hessian of rank ≤ R given by its
  /// factors (B: R×12 over the packed vertices, C: R×R symmetric): (B J)ᵀ C (B J), formed
  /// without the 12×12 product, and of an affine body's diagonal block only the upper
  /// triangle. Equal to block_hessians(Bᵀ C B, out) to round-off where both count.
  /// Instantiated for R = 1 … 5 (friction's 2; the barrier's projection, C = diag(λ)).
  template <int R>
  void low_rank_block_hessians(const Eigen::Matrix<double, R, 12>& B, const Eigen::Matrix<double, R, R>& C,
                               StencilHessian& out) const;
  /// Adds Jᵀ H_x J to the global Hessian.
  void scatter_hessian(const Eigen::Matrix<double, 12, 12>& H_x, BlockHessian& H) const;
};

}  // namespace stiffsoft
