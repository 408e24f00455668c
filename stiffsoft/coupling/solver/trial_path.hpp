#pragma once
/// @file The points a Newton direction's line search tries: a straight line in q, or, for
/// affine bodies, a turn along the rotation group (docs/newton.md, "A geodesic line search").

#include <vector>

#include <Eigen/Core>

#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// q(α) for α in (0, 1] from the iterate q along the direction p. Straight: q + α p. Geodesic:
/// a dynamic affine body with ΔA A⁻¹ = W + S (W skew, S symmetric; A, ΔA its affine matrix and
/// the direction's) whose turn matters (see the constructor) takes A(α) = exp(α W) (I + α S) A
/// and its translation + α Δp; other bodies, soft nodes and everything else move straight. Both paths leave q along p (q′(0) = p), so gᵀp is
/// the slope of either. Linear in A, a turn by θ stretches A by about θ², which the stiff
/// orthogonality potential answers with an energy of order κ ν θ⁴ that Newton's model (flat
/// along rotations at an orthogonal A) does not see; along exp(α W) the turn stretches nothing.
class TrialPath {
 public:
  /// The path from q along p. With geodesic, a body turns along exp(α W) when the orthogonality
  /// energy the straight line would add by turning it, κ ν ‖W Wᵀ‖²_F at α = 1, is at least
  /// `decrease` (J; Newton passes |gᵀp|, what the step's first order promises): a body whose turn
  /// could not cancel that moves straight, and a path on which none turns is straight.
  TrialPath(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& p, bool geodesic, double decrease);

  /// Whether q(α) = q + α p (geodesic off, or no affine body turns).
  bool straight() const { return m_turns.empty(); }

  /// q(α) into out (resized to q's size).
  void point(double alpha, Eigen::VectorXd& out) const;

 private:
  /// One affine body's turn: its DOF offset, A, the axis-angle vector w of W, and S.
  struct Turn {
    int dof;
    Eigen::Matrix3d A;
    Eigen::Vector3d w;
    Eigen::Matrix3d S;
  };
  const Eigen::VectorXd& m_q;
  const Eigen::VectorXd& m_p;
  std::vector<Turn> m_turns;
};

}  // namespace stiffsoft
