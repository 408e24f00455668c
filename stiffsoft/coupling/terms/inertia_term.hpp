#pragma once
/// @file Inertia of the incremental potential: ½ (q − q̃)ᵀ M (q − q̃), block-diagonal M.

#include <vector>

#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/coupling/terms/energy_term.hpp>

namespace stiffsoft {

/// ½ Σ_b w_b (q_b − q̃_b)ᵀ M_b (q_b − q̃_b) over the DOF blocks: M_b is an affine body's 12×12
/// mass matrix or a soft node's lumped mass m_i I₃. w_b = 1 for dynamic bodies and nodes;
/// kinematic ones use a large w_b, which pulls them onto their prescribed configuration q̃_b.
class InertiaTerm final : public EnergyTerm {
 public:
  /// The term for every DOF block; `kinematic_weight` is w_b of kinematic bodies and nodes.
  InertiaTerm(const Model& model, double kinematic_weight);
  /// See EnergyTerm::name.
  const char* name() const override { return "inertia"; }
  /// Sets q̃ for the coming step.
  void set_target(const Eigen::VectorXd& q_tilde) { m_q_tilde = q_tilde; }
  /// Sets w_b of kinematic bodies and nodes (their pull onto the prescribed configuration).
  void set_kinematic_weight(double w) { m_kinematic_weight = w; }
  /// The current q̃.
  const Eigen::VectorXd& target() const { return m_q_tilde; }
  /// See EnergyTerm::value.
  double value(const Configuration& c) const override;
  /// See EnergyTerm::add_gradient.
  void add_gradient(const Configuration& c, Eigen::VectorXd& g) const override;
  /// See EnergyTerm::add_hessian.
  void add_hessian(const Configuration& c, BlockHessian& H) const override;
  /// Couples no two blocks: see EnergyTerm::join_coupled_blocks.
  void join_coupled_blocks(const Configuration&, const Eigen::MatrixX3d&, BlockIslands&) const override {}

 private:
  struct AffineBlock {
    int block, dof;
    abd::Matrix12d M;  // M_b
    bool kinematic;
  };
  struct NodeBlock {
    int block, dof;
    double m;  // m_i
    bool kinematic;
  };
  /// w_b of a block.
  double weight(bool kinematic) const { return kinematic ? m_kinematic_weight : 1.0; }
  std::vector<AffineBlock> m_affine;
  std::vector<NodeBlock> m_nodes;
  Eigen::VectorXd m_q_tilde;
  double m_kinematic_weight;
};

}  // namespace stiffsoft
