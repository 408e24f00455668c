#pragma once
/// @file What Newton sees: a list of energy terms over the DOF vector q, each with value,
/// gradient, Hessian (projected PSD), a CCD step bound and per-configuration hooks
/// (PolyFEM's "forms"). Newton never knows which kind of body a DOF belongs to.

#include <Eigen/Core>

#include <algorithm>
#include <vector>

#include <stiffsoft/coupling/model/block_hessian.hpp>
#include <stiffsoft/coupling/model/block_islands.hpp>
#include <stiffsoft/coupling/terms/entering_pair.hpp>

namespace stiffsoft {

/// A configuration: DOFs and the surface points they place.
struct Configuration {
  const Eigen::VectorXd& q;   ///< DOFs, 12 per non-fixed body
  const Eigen::MatrixX3d& x;  ///< surface points x(q), |V|×3, m
};

/// One additive term of the incremental potential E(q).
class EnergyTerm {
 public:
  virtual ~EnergyTerm() = default;
  /// Short name for logs.
  virtual const char* name() const = 0;
  /// Called whenever the configuration changes (line-search trial, accepted iterate) before
  /// any evaluation there: rebuild configuration-dependent sets (e.g. active contacts).
  virtual void update(const Configuration&) {}
  /// E_term(q).
  virtual double value(const Configuration& c) const = 0;
  /// g += ∇E_term(q).
  virtual void add_gradient(const Configuration& c, Eigen::VectorXd& g) const = 0;
  /// H += PSD projection of ∇²E_term(q), stencil by stencil.
  virtual void add_hessian(const Configuration& c, BlockHessian& H) const = 0;
  /// Largest α ∈ [0, 1] such that q + t·dq is admissible for all t ∈ [0, α]; dx = Φ dq.
  virtual double max_step(const Configuration&, const Eigen::VectorXd& /*dq*/,
                          const Eigen::MatrixX3d& /*dx*/) const {
    return 1.0;
  }
  /// Joins in `islands` the DOF blocks this term couples anywhere on the move dx from c (a
  /// direction's or a chord's surface step): blocks it leaves in different islands share none of
  /// its stencils at any point of that move. The default joins every block, which is always
  /// right and gives every block the same step length.
  virtual void join_coupled_blocks(const Configuration&, const Eigen::MatrixX3d& /*dx*/, BlockIslands& islands) const {
    islands.join_all();
  }
  /// max_step by island: lowers bound[i] to the largest α such that q + t·dq is admissible for
  /// this term's stencils in island i for all t ∈ [0, α]. Called after every term's
  /// join_coupled_blocks for the same move, with `islands` numbered. The default lowers every
  /// island's bound to max_step.
  virtual void max_step_per_island(const Configuration& c, const Eigen::VectorXd& dq, const Eigen::MatrixX3d& dx,
                                   const BlockIslands& /*islands*/, std::vector<double>& bound) const {
    const double alpha = max_step(c, dq, dx);
    for (double& b : bound) b = std::min(b, alpha);
  }
  /// Appends to `out` the pairs outside this term's reach that the move last bounded from c
  /// (max_step, or join_coupled_blocks then max_step_per_island) brings closer than CCD lets it
  /// (time below 1), for the one-sided springs Newton solves such a direction again with
  /// (solver/entering_springs.hpp). The default has none.
  virtual void entering_pairs(const Configuration&, std::vector<EnteringPair>& /*out*/) const {}
  /// Called with each Newton direction dq (surface step dx) and the Hessian H it was solved
  /// with. A term whose Hessian model should depend on where the step goes (friction: a slide
  /// the full step would reverse) may add the change of its model to H and return true; Newton
  /// then solves once more with the revised H.
  virtual bool revise_hessian(const Configuration&, const Eigen::VectorXd& /*dq*/, const Eigen::MatrixX3d& /*dx*/,
                              BlockHessian& /*H*/) const {
    return false;
  }
  /// After each accepted Newton iteration (e.g. adapt the barrier stiffness). Returns true
  /// when it changed the term's value at c, so that Newton evaluates E there again (otherwise
  /// it keeps the accepted trial's E).
  virtual bool end_iteration(const Configuration&) { return false; }
  /// Largest relative change of a gap the term keeps open along dx (0: none).
  virtual double relative_gap_change(const Configuration&, const Eigen::MatrixX3d& /*dx*/) const { return 0.0; }
  /// Largest tangential move along dx of a friction stencil in its stick zone, as a fraction
  /// of the zone's width ε_v h (0: none).
  virtual double stick_zone_step(const Configuration&, const Eigen::MatrixX3d& /*dx*/) const { return 0.0; }
};

}  // namespace stiffsoft
