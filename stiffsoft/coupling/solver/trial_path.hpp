#pragma once
/// @file The points a Newton direction's line search tries: a straight line in q, or, for
/// affine bodies, a turn along the rotation group (docs/newton.md, "A geodesic line search").

#include <vector>

#include <Eigen/Core>

#include <stiffsoft/coupling/model/block_islands.hpp>
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
  /// energy the straight line would add by turning it, κ ν ‖W Wᵀ‖²_F at α = 1 (J), is at least
  /// `decrease`; a path on which no body turns is straight. Newton passes |gᵀp|, in the units of
  /// its energy, where V⊥ enters as β h² V⊥: so a body turns when its stretch in those units is
  /// at least the fraction β h² / (1 s²) of the decrease (1e-4 at h = 1/100 s, 1.7e-5 at 1/240,
  /// 1e-6 at 1/1000). A fraction fixed at 0 (every turn), 1e-5, 1e-4 or 1e-3 took more
  /// iterations on some scene or time step (docs/newton.md, session 41).
  TrialPath(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& p, bool geodesic, double decrease);

  /// Whether q(α) = q + α p (geodesic off, or no affine body turns).
  bool straight() const { return m_turns.empty(); }

  /// q(α) into out (resized to q's size).
  void point(double alpha, Eigen::VectorXd& out) const;
  /// Each DOF block b at its own point of the path, q_b(alpha[b]) (one entry per block), into
  /// out: Newton's geodesic trial for islands that CCD cut at different fractions.
  void point(const Model& model, const std::vector<double>& alpha, Eigen::VectorXd& out) const;
  /// The orthogonality energy (J) that moving the turning bodies of the islands CCD cut, each
  /// only the fraction βᵢ = bound[island] < 1 of its chord from q to q(α), adds over sending
  /// them to the path's own points q(α βᵢ): part of a chord between two turns is no turn.
  double chord_stretch(const BlockIslands& islands, const std::vector<double>& bound, double alpha) const;

 private:
  /// One affine body's turn: its DOF offset and block, κ ν, A, the axis-angle vector w of W, and S.
  struct Turn {
    int dof, block;
    double kappa_volume;
    Eigen::Matrix3d A;
    Eigen::Vector3d w;
    Eigen::Matrix3d S;
  };
  /// The turning body's affine matrix at α.
  static Eigen::Matrix3d turned(const Turn& t, double alpha);

  const Eigen::VectorXd& m_q;
  const Eigen::VectorXd& m_p;
  std::vector<Turn> m_turns;
};

}  // namespace stiffsoft
