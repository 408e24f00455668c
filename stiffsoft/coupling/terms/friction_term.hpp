#pragma once
/// @file Lagged smoothed friction (Li et al. 2020, §5): D(x) = Σ_k μ λ_k f₀(‖u_k‖), with normal
/// forces λ_k and tangent bases lagged at the step's start and u_k the tangential relative
/// displacement over the step. Only built when μ > 0.

#include <cstdint>
#include <vector>

#include <stiffsoft/coupling/contact/friction.hpp>
#include <stiffsoft/coupling/model/stencil_jacobian.hpp>
#include <stiffsoft/coupling/terms/barrier_term.hpp>

namespace stiffsoft {

/// The friction term of one time step.
class FrictionTerm final : public EnergyTerm {
 public:
  /// μ ≥ 0 and ε_v h (m): the tangential displacement below which static friction is smoothed.
  FrictionTerm(const Model& model, double mu, double epsv_h);
  /// See EnergyTerm::name.
  const char* name() const override { return "friction"; }
  /// Lags normal forces and bases from the barrier's active set at the start-of-step
  /// configuration c (whose surface x becomes xⁿ).
  void lag(const Configuration& c, const BarrierTerm& barrier);
  /// Lags normal forces and bases again, from the barrier's active set at c, keeping xⁿ: the
  /// tangential displacements still count from the step's start.
  void relag(const Configuration& c, const BarrierTerm& barrier);
  /// See EnergyTerm::value.
  double value(const Configuration& c) const override;
  /// See EnergyTerm::add_gradient.
  void add_gradient(const Configuration& c, Eigen::VectorXd& g) const override;
  /// See EnergyTerm::add_hessian: the PSD-projected exact Hessian of every stencil, or its
  /// majorizer on the stencils revise_hessian has switched to it since the last lag.
  void add_hessian(const Configuration& c, BlockHessian& H) const override;
  /// Joins the blocks of every lagged stencil: see EnergyTerm::join_coupled_blocks.
  void join_coupled_blocks(const Configuration& c, const Eigen::MatrixX3d& dx, BlockIslands& islands) const override;
  /// On every stencil whose slide the full step dx would reverse (contact/friction.hpp,
  /// step_reverses_slide), replaces its Hessian in H by the majorizer; true if any. Such a
  /// stencil keeps the majorizer in add_hessian for the rest of the lag (it bounds friction's
  /// curvature from above, so every direction stays a descent direction), so that a later
  /// iteration solves once where it would otherwise revise the same stencil again.
  bool revise_hessian(const Configuration& c, const Eigen::VectorXd& dq, const Eigen::MatrixX3d& dx,
                      BlockHessian& H) const override;
  /// See EnergyTerm::stick_zone_step: over the stencils with λ > 0 and ‖u‖ < ε_v h at c,
  /// max ‖T dx‖ / (ε_v h).
  double stick_zone_step(const Configuration& c, const Eigen::MatrixX3d& dx) const override;
  /// Friction force −∇_x D on every surface vertex, |V|×3 (energy units, as the barrier's).
  Eigen::MatrixX3d vertex_forces(const Configuration& c) const;
  /// Σ_k λ_k over the lagged stencils that touch each body (indexed like Model::bodies; a
  /// stencil between two bodies counts for both), in the energy's units.
  std::vector<double> normal_force_per_body() const;
  /// The same sums for the barrier's active set at c: what lag(c, barrier) would give. Keeps
  /// the stencils it makes, which the next lag or relag at c, with the same contacts and κ,
  /// takes instead of making them again (the next step starts where this one ends).
  std::vector<double> normal_force_per_body(const Configuration& c, const BarrierTerm& barrier);
  /// Number of lagged friction stencils.
  size_t size() const { return m_stencils.size(); }

  /// How many stencils with λ > 0 stick (‖T u‖ < ε_v h) and how many slide at a configuration.
  struct StickSlip {
    int sticking = 0;  ///< stencils whose slide since xⁿ is inside the stick zone
    int sliding = 0;   ///< stencils whose slide is outside it
  };
  /// The stick/slip counts at c.
  StickSlip stick_slip(const Configuration& c) const;
  /// See EnergyTerm::end_iteration: counts the stencils that moved between sticking and
  /// sliding since the previous accepted iterate (a diagnostic; E is unchanged, so false).
  bool end_iteration(const Configuration& c) override;
  /// Changes between sticking and sliding from one accepted iterate to the next, summed over
  /// the stencils since the last lag() (relag() keeps counting, from the new stencils' first
  /// iterate on).
  int stick_slip_flips() const { return m_flips; }

 private:
  contact::Vector12d displacement(const Configuration& c, size_t k) const;
  /// Whether a stencil sticks or slides at a configuration (None: no normal force).
  enum class Slip : char { None, Sticking, Sliding };
  /// Stencil k's Slip at c.
  Slip slip(const Configuration& c, size_t k) const;
  const Model& m_model;
  double m_mu, m_epsv_h;
  Eigen::MatrixX3d m_x_lag;
  std::vector<contact::FrictionStencil> m_stencils;
  std::vector<std::array<int, 4>> m_vertices;
  std::vector<contact::Vector12d> m_lagged;     ///< each stencil's vertices at xⁿ
  std::vector<StencilJacobian> m_jacobians;     ///< each stencil's map from the DOFs
  /// The barrier's block_rank() at the lag: the owners' parts of friction's assembly.
  std::vector<int> m_block_rank;
  /// Whether each stencil has been switched to its majorizer (revise_hessian; cleared by relag)
  mutable std::vector<char> m_majorized;
  std::vector<Slip> m_slip;  ///< each stencil's Slip at the last accepted iterate (None before the first)
  /// Stencils normal_force_per_body(c, barrier) made, with what they were made from.
  struct Made {
    std::vector<contact::FrictionStencil> stencils;
    const BarrierTerm* barrier = nullptr;  ///< whose contacts
    std::uint64_t build = 0;               ///< their build (BarrierTerm::build; 0: none)
    double kappa = 0;                      ///< the barrier's κ
  };
  Made m_made;
  int m_flips = 0;            ///< see stick_slip_flips
};

}  // namespace stiffsoft
