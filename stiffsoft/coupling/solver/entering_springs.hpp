#pragma once
/// @file Newton's direction when CCD cuts it at pairs outside the barrier's reach: solved again
/// with a one-sided spring on each such pair's linearised gap (docs/newton.md, "Springs on the
/// pairs CCD finds entering"). The barrier is zero beyond d̂, so Newton's model does not know a
/// pair the step is about to hit; CCD then stops the whole island at a tenth of that pair's gap
/// and the next iterations push it back out of the barrier's steep part ("TOI locking"; AL-IPC,
/// arXiv 2512.12151, adds such pairs to its constraints). Here only the direction changes: the
/// energy and the line search stay as they are.

#include <functional>
#include <vector>

#include <Eigen/Core>

#include <stiffsoft/coupling/model/block_hessian.hpp>
#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/coupling/model/stencil_jacobian.hpp>
#include <stiffsoft/coupling/terms/entering_pair.hpp>

namespace stiffsoft {

/// The springs of one Newton direction. The model it minimises is
///   ½ pᵀ H p + gᵀ p + Σᵢ ½ kᵢ min(0, nᵢᵀ Jᵢ p + sᵢ)²,
/// nᵢ, sᵢ the pair's normal and slack, Jᵢ its stencil's Jacobian, kᵢ = kSpringScale mᵢ with mᵢ
/// the largest mass that moves one of its vertices (a body's, or a soft node's lumped mass): in
/// the units of Newton's energy ½ ‖q − q̃‖²_M + β h² V, kSpringScale times the inertia of what
/// it stops. The model is zero at p = 0, so its minimiser is a descent direction of the energy.
class EnteringSprings {
 public:
  /// Spring stiffness over the mass it stops (docs/newton.md, session 44: 1e5, 1e6 and 1e7 took
  /// as many iterations on medium and full at h = 1/240; 1e3 / h² s², a thousand times stiffer
  /// at 1/100, let a spring hold a pair by deforming an affine body more than its orthogonality
  /// potential resists, and full at 1/100 then stopped at the rigidity bound).
  static constexpr double kSpringScale = 1e5;
  /// Solves per direction: the first kFreeRounds add and drop springs by the sign of the
  /// linearised gap, the later ones only add (a set that flips between two solves stops there).
  static constexpr int kRounds = 2;
  static constexpr int kFreeRounds = 1;

  /// Solves H p = −g for a given g: Newton's linear solve on the current H.
  using Solve = std::function<bool(const Eigen::VectorXd& g, Eigen::VectorXd& p)>;

  /// A spring on each of the pairs.
  EnteringSprings(const Model& model, std::vector<EnteringPair> pairs);

  /// Minimises the model over p with H (Newton's, revised) and g, starting from every spring
  /// acting, by up to kRounds solves; replaces p and returns true when every solve succeeded
  /// and the result is a descent direction (gᵀp < 0), else leaves p. H holds the springs while
  /// solving and loses them again (its pattern may keep their blocks, at zero).
  bool solve(BlockHessian& H, const Eigen::VectorXd& g, const Solve& solve_h, Eigen::VectorXd& p);

  /// Number of pairs held.
  std::size_t size() const { return m_pairs.size(); }

 private:
  /// Adds (sign = 1) or removes (−1) spring i's Hessian k nnᵀ in H.
  void add_hessian(std::size_t i, double sign, BlockHessian& H) const;

  const Model& m_model;
  std::vector<EnteringPair> m_pairs;
  std::vector<StencilJacobian> m_jacobians;
  std::vector<double> m_stiffness;
};

}  // namespace stiffsoft
