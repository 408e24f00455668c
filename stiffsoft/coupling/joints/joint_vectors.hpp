#pragma once
/// @file The world vectors a joint is written in, as affine functions of q: a point
/// x = A x̄ + p of an affine body, a direction A w̄ of it, a soft node's position, or a constant
/// (world, fixed bodies). A joint potential stacks k of them, y = [v₁; …; v_k] = G q + c, with
/// G constant (affine bodies and soft nodes are linear in q), so its gradient and Hessian in q
/// are Gᵀ ∇_y φ and Gᵀ ∇²_y φ G.

#include <Eigen/Core>
#include <vector>

#include <stiffsoft/coupling/model/block_hessian.hpp>
#include <stiffsoft/coupling/joints/joint.hpp>
#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// One world vector carried by a joint end.
struct JointVector {
  int block = -1;                                      ///< DOF block it depends on; −1: constant
  int dof = -1;                                        ///< first DOF of that block in q
  int size = 0;                                        ///< 12 (affine body) or 3 (soft node); 0 when constant
  Eigen::Matrix<double, 3, Eigen::Dynamic> J;          ///< ∂v/∂q_block, 3 × size
  Eigen::Vector3d constant = Eigen::Vector3d::Zero();  ///< v when constant (m or dimensionless)
  /// v(q).
  Eigen::Vector3d value(const Eigen::VectorXd& q) const;
};

/// The point of a joint end: its anchor on an affine body, its soft node, or a world point.
/// `anchor` overrides the end's anchor (body frame for affine ends, world for the world).
JointVector end_point(const Model& model, const JointEnd& end, const Eigen::Vector3d& anchor);
/// The direction A w̄ of an affine end's body-frame vector w̄ (a world end: w̄ itself, in the
/// world frame; a fixed body: its constant A w̄). Throws std::invalid_argument for a soft node.
JointVector end_direction(const Model& model, const JointEnd& end, const Eigen::Vector3d& w_bar);

/// k stacked joint vectors y = [v₁; …; v_k] and their map to the DOF blocks they depend on.
class JointVectors {
 public:
  /// The stack of `vectors`, in order.
  explicit JointVectors(std::vector<JointVector> vectors);
  /// Number of stacked vectors k (y has 3k entries).
  int count() const { return int(m_vectors.size()); }
  /// y(q), 3k.
  Eigen::VectorXd gather(const Eigen::VectorXd& q) const;
  /// g += Gᵀ g_y.
  void scatter_gradient(const Eigen::VectorXd& g_y, Eigen::VectorXd& g) const;
  /// H += Gᵀ H_y G, block by block.
  void scatter_hessian(const Eigen::MatrixXd& H_y, BlockHessian& H) const;
  /// True when no vector depends on q (the potential is constant).
  bool constant() const { return m_blocks.empty(); }

 private:
  struct Slot {
    int block, dof;
    Eigen::MatrixXd G;  // ∂y/∂q_block, 3k × size
  };
  std::vector<JointVector> m_vectors;
  std::vector<Slot> m_blocks;
};

}  // namespace stiffsoft
