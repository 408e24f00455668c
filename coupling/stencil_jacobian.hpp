#pragma once
/// @file How a contact stencil's surface points depend on body DOFs: x_stencil = Σ_s J_s q_s
/// over the (at most two) bodies of the stencil, with J_s stacking J(x̄) of the vertices of
/// body s. Fixed bodies carry no DOFs and drop out.

#include <Eigen/Core>
#include <array>

#include "coupling/block_hessian.hpp"
#include "coupling/model.hpp"

namespace stiffsoft {

/// The linear map from the DOFs of a stencil's bodies to its packed vertex positions.
struct StencilJacobian {
  std::array<int, 2> block{-1, -1};    ///< DOF block (dof / 12) of each body slot, −1 if none
  int slots = 0;                       ///< number of body slots with DOFs
  Eigen::Matrix<double, 12, 24> J = Eigen::Matrix<double, 12, 24>::Zero();  ///< ∂x_stencil/∂(q_slot0, q_slot1)

  /// Builds the map for the given stencil vertices (−1 entries unused).
  StencilJacobian(const Model& model, const std::array<int, 4>& vertices);

  /// Adds Jᵀ g_x to the global gradient g.
  void scatter_gradient(const Eigen::Matrix<double, 12, 1>& g_x, Eigen::VectorXd& g) const;
  /// Adds Jᵀ H_x J to the global Hessian.
  void scatter_hessian(const Eigen::Matrix<double, 12, 12>& H_x, BlockHessian& H) const;
};

}  // namespace stiffsoft
