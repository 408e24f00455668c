#pragma once
/// @file Time integrators of the incremental potential
///   q⁺ = argmin ½‖q − q̃‖²_M + β h² Ψ(q) + contact,
/// (design.md; Chen, Li et al. 2022 for BDF-2 as the restitution model).

#include <Eigen/Core>

namespace stiffsoft {

/// Time integrator of the incremental potential.
enum class Integrator {
  BackwardEuler,  ///< q̃ = qⁿ + h q̇ⁿ + h² a, β = 1
  BDF2            ///< q̃ = 4/3 qⁿ − 1/3 qⁿ⁻¹ + 8/9 h q̇ⁿ − 2/9 h q̇ⁿ⁻¹ + 4/9 h² a, β = 4/9
};

/// β: the weight of h² in front of the potentials.
inline double integrator_beta(Integrator integrator) {
  return integrator == Integrator::BDF2 ? 4.0 / 9.0 : 1.0;
}

/// q̃ of the step from qⁿ (and qⁿ⁻¹, q̇ⁿ⁻¹ for BDF-2) with constant acceleration a (h² a enters
/// scaled by β). BDF-2's first step takes the history of a constant-velocity past,
/// q⁻¹ = q⁰ − h q̇⁰ and q̇⁻¹ = q̇⁰, for which q̃ reduces to q⁰ + h q̇⁰ + β h² a.
inline Eigen::VectorXd predicted_q(Integrator integrator, double h,
                                   const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                   const Eigen::VectorXd& q_prev, const Eigen::VectorXd& qdot_prev,
                                   const Eigen::VectorXd& a) {
  if (integrator == Integrator::BackwardEuler) return q + h * qdot + h * h * a;
  return 4.0 / 3.0 * q - 1.0 / 3.0 * q_prev + 8.0 / 9.0 * h * qdot - 2.0 / 9.0 * h * qdot_prev +
         4.0 / 9.0 * h * h * a;
}

/// c in δq̇⁺ = c δq⁺ / h: how the velocity after the step follows a change of its result
/// (BE 1, BDF-2 3/2; see updated_qdot).
inline double velocity_coefficient(Integrator integrator) { return integrator == Integrator::BDF2 ? 1.5 : 1.0; }

/// q̇⁺ after the step: BE (q⁺ − qⁿ)/h; BDF-2 (3q⁺ − 4qⁿ + qⁿ⁻¹)/(2h).
inline Eigen::VectorXd updated_qdot(Integrator integrator, double h,
                                    const Eigen::VectorXd& q_new, const Eigen::VectorXd& q,
                                    const Eigen::VectorXd& q_prev) {
  if (integrator == Integrator::BackwardEuler) return (q_new - q) / h;
  return (3.0 * q_new - 4.0 * q + q_prev) / (2.0 * h);
}

}  // namespace stiffsoft
