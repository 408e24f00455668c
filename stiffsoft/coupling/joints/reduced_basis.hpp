#pragma once
/// @file The change of variables that removes linear equalities C q = d exactly:
/// q = N z + q_p. One "slave" DOF per independent row is eliminated by Gaussian elimination
/// with pivoting (reduced row echelon form over the columns C touches), so chains and closed
/// loops work and redundant rows are detected. Newton then solves (Nᵀ H N) dz = −Nᵀ g and
/// steps dq = N dz, which never leaves the constraint set.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include <stiffsoft/coupling/joints/linear_constraints.hpp>
#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// q = N z + q_p over the solutions of C q = d.
class ReducedBasis {
 public:
  /// Eliminates the rows of `constraints` over the model's DOFs. Slaves are chosen, among the
  /// entries within a factor 10 of a row's largest, preferably as translations p of affine
  /// bodies and soft-node positions (so projecting a pose moves bodies rather than shearing
  /// them). A row that is a combination of earlier ones is recorded in redundant_rows(); an
  /// inconsistent one (same left side, different d) throws std::invalid_argument naming its
  /// joint.
  ReducedBasis(const Model& model, const LinearConstraints& constraints);
  /// N, n × r (sparse).
  const Eigen::SparseMatrix<double>& N() const { return m_N; }
  /// Number of reduced coordinates r = n − (independent rows).
  int reduced_size() const { return int(m_N.cols()); }
  /// Number of DOFs n.
  int full_size() const { return int(m_N.rows()); }
  /// The closest point of the constraint set that keeps q's non-slave DOFs: N z(q) + q_p.
  Eigen::VectorXd project(const Eigen::VectorXd& q) const;
  /// Nᵀ g.
  Eigen::VectorXd reduce(const Eigen::VectorXd& g) const { return m_Nt * g; }
  /// N dz.
  Eigen::VectorXd expand(const Eigen::VectorXd& dz) const { return m_N * dz; }
  /// The upper triangle of Nᵀ H N from the upper triangle of symmetric H.
  Eigen::SparseMatrix<double> reduce_upper(const Eigen::SparseMatrix<double>& upper) const;
  /// Rows of C that were combinations of earlier rows (and consistent with them).
  const std::vector<int>& redundant_rows() const { return m_redundant; }
  /// The eliminated DOFs, one per independent row.
  const std::vector<int>& slaves() const { return m_slaves; }

 private:
  Eigen::SparseMatrix<double> m_N, m_Nt;
  Eigen::VectorXd m_q_p;
  std::vector<int> m_free;  // DOF of each reduced coordinate
  std::vector<int> m_slaves;
  std::vector<int> m_redundant;
};

}  // namespace stiffsoft
