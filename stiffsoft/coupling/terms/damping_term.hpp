#pragma once
/// @file Lagged Rayleigh damping (Chen, Li et al. 2022): a dissipation ½ νᵀ K ν with ν the
/// velocity and K a PSD matrix frozen at the step's start xⁿ,
///  - contact: K = k_d ∇²B(xⁿ), B the contact barrier energy (J), k_d (s) per scene or per
///    body pair;
///  - joints: K = c ∇s(xⁿ) ∇s(xⁿ)ᵀ, s the joint's free coordinate (hinge angle, prismatic slide,
///    distance), c per joint (N·m·s/rad or N·s/m): a viscous damper on that coordinate, i.e.
///    Rayleigh damping of the potential ½ s² with k_d = c; ball and cone-twist joints:
///    K = c Jᵀ J with J = ∂ω/∂q̇ at xⁿ, ω the relative angular velocity of the two bodies
///    (joint_measures.hpp, relative_angular_velocity_jacobian): a torque −c ω on body a.
/// With ν = (q − qⁿ)/h the damping force is −K ν, which enters the incremental potential as
/// ½ β h (q − qⁿ)ᵀ K (q − qⁿ) (gradient β h² K ν).

#include <array>
#include <vector>

#include <stiffsoft/coupling/joints/joint_vectors.hpp>
#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/coupling/model/stencil_jacobian.hpp>
#include <stiffsoft/coupling/terms/barrier_term.hpp>
#include <stiffsoft/coupling/terms/energy_term.hpp>

namespace stiffsoft {

/// k_d of the contacts between two bodies, replacing the scene-wide value for that pair.
struct ContactPairDamping {
  int body_a = -1;     ///< body index in Model::bodies
  int body_b = -1;     ///< body index in Model::bodies (body_a for a soft body's self-contact)
  double damping = 0;  ///< k_d (s), ≥ 0
};

/// The k_d (s) of a contact whose stencil touches `bodies` (one or two distinct bodies): the
/// pair's value when `pairs` lists that pair (in either order), else `k_d`.
double contact_pair_damping(const std::array<int, 2>& bodies, double k_d, const std::vector<ContactPairDamping>& pairs);

/// The lagged damping of one step, contact and joints together.
class DampingTerm final : public EnergyTerm {
 public:
  /// An empty term over the model.
  explicit DampingTerm(const Model& model) : m_model(model) {}
  /// See EnergyTerm::name.
  const char* name() const override { return "damping"; }
  /// Forgets the last step's matrices; `q_n` (DOFs at the step's start) and the incremental
  /// weight β h (s) of the step to come.
  void start_step(const Eigen::VectorXd& q_n, double beta_h);
  /// Adds contact damping k_d ∇²B(xⁿ) over the barrier's active contacts at c_n. `barrier`
  /// is the barrier term (value in units of β h² × energy); k_d in s, replaced by the pair's
  /// value for contacts between the bodies of an entry of `pairs`.
  void lag_contact(const Configuration& c_n, const BarrierTerm& barrier, double k_d,
                   const std::vector<ContactPairDamping>& pairs, double beta_h2);
  /// Adds the damping of every joint with damping c > 0, at q_n.
  void lag_joints();
  /// True when nothing is damped this step.
  bool empty() const { return m_contacts.empty() && m_joints.empty(); }
  /// See EnergyTerm::value.
  double value(const Configuration& c) const override;
  /// See EnergyTerm::add_gradient.
  void add_gradient(const Configuration& c, Eigen::VectorXd& g) const override;
  /// See EnergyTerm::add_hessian.
  void add_hessian(const Configuration& c, BlockHessian& H) const override;
  /// Joins the blocks of every damped contact, and every block when a joint is damped: see
  /// EnergyTerm::join_coupled_blocks.
  void join_coupled_blocks(const Configuration& c, const Eigen::MatrixX3d& dx, BlockIslands& islands) const override;

 private:
  struct ContactElement {
    StencilJacobian J;
    std::array<int, 4> vertices;
    Eigen::Matrix<double, 12, 12> K;  // β h k_d ∇²B (already weighted)
    Eigen::Matrix<double, 12, 1> x_n;
  };
  struct JointElement {
    JointVectors vectors;
    Eigen::MatrixXd W;  // √(β h c) ∂s/∂y at qⁿ, one row per damped coordinate: the element is ½ |W Δy|²
    Eigen::VectorXd y_n;
  };
  const Model& m_model;
  Eigen::VectorXd m_q_n;
  double m_beta_h = 0;
  std::vector<ContactElement> m_contacts;
  std::vector<JointElement> m_joints;
};

}  // namespace stiffsoft
