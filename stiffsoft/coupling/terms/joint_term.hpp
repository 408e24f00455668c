#pragma once
/// @file β h² Σ φ(s(y)): the joints' nonlinear equalities as stiff penalties (distance, the
/// off-axis drift of prismatic joints) and their inequalities as barrier potentials (bounded
/// distance, sliding range, rotation range), which also bound Newton's line search so a limit
/// is never crossed (Chen, Li et al. 2022). Linear equalities are not here: they are
/// eliminated (joints/reduced_basis.hpp).

#include <vector>

#include <stiffsoft/coupling/joints/joint_measures.hpp>
#include <stiffsoft/coupling/joints/joint_vectors.hpp>
#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/coupling/terms/energy_term.hpp>

namespace stiffsoft {

/// How a joint potential turns its measure s into energy φ(s) (J).
enum class JointWrap {
  Penalty,       ///< ½ k (s − s₀)²
  HalfLinear,    ///< ½ k s (s is itself a squared distance)
  LowerBarrier,  ///< κ b((s − s_min)/ĝ): keeps s > s_min; b(x) = −(x − 1)² ln x for x < 1, else 0
  UpperBarrier   ///< κ b((s_max − s)/ĝ): keeps s < s_max
};

/// One scalar potential of one joint.
struct JointPotential {
  int joint = -1;                                  ///< index in Model::joints
  JointMeasure measure = JointMeasure::Distance;   ///< what it measures
  JointWrap wrap = JointWrap::Penalty;             ///< how it becomes energy
  double k = 0;                                    ///< penalty k (N/m; N/m for ½ k s with s in m²) or barrier κ (J)
  double target = 0;                               ///< s₀, s_min or s_max (m or rad)
  double activation = 0;                           ///< barrier activation gap ĝ (m or rad)
  /// φ(s) (J); +∞ outside a barrier's admissible side.
  double energy(double s) const;
  /// φ'(s).
  double first_derivative(double s) const;
  /// φ''(s).
  double second_derivative(double s) const;
  /// The barrier's gap (s − s_min or s_max − s); +∞ for penalties.
  double gap(double s) const;
  /// True for a barrier farther than its activation gap from its limit: φ, φ' and φ'' are 0
  /// there, so its measure is not differentiated (the bend angle's derivatives are singular at
  /// bend 0, where a swing limit is never active).
  bool inactive(double s) const;
};

/// The potentials of every joint of a model (none for ball and hinge joints without limits).
/// A cone-twist joint has an upper barrier on its bend angle (swing) and lower/upper barriers
/// on its twist angle.
std::vector<std::pair<JointPotential, JointVectors>> joint_potentials(const Model& model);

/// The joints' penalties and limit barriers.
class JointTerm final : public EnergyTerm {
 public:
  /// `scale` is β h² (s²).
  JointTerm(const Model& model, double scale);
  /// See EnergyTerm::name.
  const char* name() const override { return "joints"; }
  /// See EnergyTerm::value.
  double value(const Configuration& c) const override;
  /// See EnergyTerm::add_gradient.
  void add_gradient(const Configuration& c, Eigen::VectorXd& g) const override;
  /// See EnergyTerm::add_hessian (each potential's y-Hessian projected PSD).
  void add_hessian(const Configuration& c, BlockHessian& H) const override;
  /// Largest α (halving from 1) for which, at 8 samples of [0, α], every barrier's gap stays
  /// above 10 % of its current value and every measure moves by less than 0.5 between samples
  /// (no angle wraps around ±π).
  double max_step(const Configuration& c, const Eigen::VectorXd& dq, const Eigen::MatrixX3d& dx) const override;
  /// True when the model's joints have no penalty or barrier.
  bool empty() const { return m_potentials.empty(); }
  /// Each joint's potentials' energy φ (J, unscaled) at q, indexed like Model::joints.
  std::vector<double> joint_energies(const Eigen::VectorXd& q, int joints) const;
  /// The potentials, with the vectors they read.
  const std::vector<std::pair<JointPotential, JointVectors>>& potentials() const { return m_potentials; }

 private:
  std::vector<std::pair<JointPotential, JointVectors>> m_potentials;
  double m_scale;
};

}  // namespace stiffsoft
