#pragma once
/// @file The joints' linear equalities C q = d (m). For affine bodies x = A x̄ + p is linear
/// in q, so a point connection p_a + A_a x̄_a = p_b + A_b x̄_b (or = a world point, or a soft
/// node's position) is three linear rows (ball and cone-twist joints, plus three per further
/// pinned soft node); a hinge is two such points on its axis, and a locked relative orientation
/// (prismatic joints) is A_a w̄_a,i = A_b w̄_b,i for the three world axes.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

#include <stiffsoft/coupling/joints/joint_vectors.hpp>
#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// All linear joint equalities of a model, three rows per equal vector pair.
struct LinearConstraints {
  Eigen::SparseMatrix<double> C;  ///< m × n (n = Model::num_dofs)
  Eigen::VectorXd d;              ///< m
  std::vector<int> row_joint;     ///< joint (Model::joints) of each row
  std::vector<char> row_is_point; ///< 1 where the row's pair are points (its multiplier is a force), 0 for directions
  /// Number of rows m.
  int rows() const { return int(d.size()); }
};

/// The pairs of world vectors that a joint keeps equal (empty for penalty-only kinds).
std::vector<std::pair<JointVector, JointVector>> linear_equalities(const Model& model, const JointModel& joint);

/// C and d of every joint of the model.
LinearConstraints linear_joint_constraints(const Model& model);

/// The largest violation |C q − d| over each joint's rows, per joint (m); 0 for joints without rows.
std::vector<double> joint_violations(const LinearConstraints& constraints, const Eigen::VectorXd& q, int joints);

}  // namespace stiffsoft
