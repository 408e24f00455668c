#include <stiffsoft/coupling/joints/reduced_basis.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stiffsoft {

ReducedBasis::ReducedBasis(const Model& model, const LinearConstraints& constraints) {
  const int n = model.num_dofs;
  const int m = constraints.rows();
  // The columns C touches, dense: m × k with k small (a few bodies' DOFs per joint).
  std::vector<int> columns;
  for (int c = 0; c < constraints.C.outerSize(); ++c)
    if (constraints.C.col(c).nonZeros() > 0) columns.push_back(c);
  const int k = int(columns.size());
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(m, k);
  for (int j = 0; j < k; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(constraints.C, columns[j]); it; ++it) R(it.row(), j) = it.value();
  Eigen::VectorXd rhs = constraints.d;
  // Preferred slaves: affine translations and soft-node positions.
  std::vector<char> preferred(n, 0);
  for (const DofBlock& b : model.blocks)
    for (int i = 0; i < (b.size == 12 ? 3 : b.size); ++i) preferred[b.offset + i] = 1;

  std::vector<int> pivot_row, pivot_column;  // pivot_column: index into `columns`
  for (int i = 0; i < m; ++i) {
    const double scale = constraints.C.row(i).norm();
    const double largest = k ? R.row(i).cwiseAbs().maxCoeff() : 0.0;
    if (largest <= 1e-10 * std::max(scale, 1e-300)) {
      const double d_scale = std::max(1.0, std::abs(constraints.d[i]));
      if (std::abs(rhs[i]) > 1e-9 * d_scale)
        throw std::invalid_argument("joint " + model.joints[constraints.row_joint[i]].name +
                                    ": its linear constraint row " + std::to_string(i) +
                                    " contradicts the other joints' (inconsistent by " + std::to_string(rhs[i]) +
                                    " m)");
      m_redundant.push_back(i);
      continue;
    }
    int best = -1;
    for (int pass = 0; pass < 2 && best < 0; ++pass)
      for (int j = 0; j < k; ++j) {
        const double a = std::abs(R(i, j));
        if (a < 0.1 * largest || (pass == 0 && !preferred[columns[j]])) continue;
        if (best < 0 || a > std::abs(R(i, best))) best = j;
      }
    const double pivot = R(i, best);
    R.row(i) /= pivot;
    rhs[i] /= pivot;
    for (int r = 0; r < m; ++r) {
      if (r == i || R(r, best) == 0) continue;
      const double f = R(r, best);
      R.row(r) -= f * R.row(i);
      rhs[r] -= f * rhs[i];
    }
    pivot_row.push_back(i);
    pivot_column.push_back(best);
  }

  std::vector<int> slave_of(n, -1);  // pivot index of a slave DOF
  for (std::size_t s = 0; s < pivot_row.size(); ++s) {
    slave_of[columns[pivot_column[s]]] = int(s);
    m_slaves.push_back(columns[pivot_column[s]]);
  }
  std::vector<int> reduced_index(n, -1);
  for (int dof = 0; dof < n; ++dof)
    if (slave_of[dof] < 0) {
      reduced_index[dof] = int(m_free.size());
      m_free.push_back(dof);
    }
  std::vector<Eigen::Triplet<double>> triplets;
  m_q_p = Eigen::VectorXd::Zero(n);
  for (int dof = 0; dof < n; ++dof) {
    if (slave_of[dof] < 0) {
      triplets.emplace_back(dof, reduced_index[dof], 1.0);
      continue;
    }
    const int s = slave_of[dof];
    const int i = pivot_row[s];
    // q_slave = rhs_i − Σ_{free j} R(i, j) q_j.
    m_q_p[dof] = rhs[i];
    for (int j = 0; j < k; ++j) {
      if (j == pivot_column[s] || slave_of[columns[j]] >= 0 || R(i, j) == 0) continue;
      triplets.emplace_back(dof, reduced_index[columns[j]], -R(i, j));
    }
  }
  m_N.resize(n, int(m_free.size()));
  m_N.setFromTriplets(triplets.begin(), triplets.end());
  m_Nt = m_N.transpose();
}

Eigen::VectorXd ReducedBasis::project(const Eigen::VectorXd& q) const {
  Eigen::VectorXd z(m_free.size());
  for (std::size_t i = 0; i < m_free.size(); ++i) z[i] = q[m_free[i]];
  return m_N * z + m_q_p;
}

Eigen::SparseMatrix<double> ReducedBasis::reduce_upper(const Eigen::SparseMatrix<double>& upper) const {
  const Eigen::SparseMatrix<double> S = upper.selfadjointView<Eigen::Upper>();
  const Eigen::SparseMatrix<double> reduced = m_Nt * S * m_N;
  return reduced.triangularView<Eigen::Upper>();
}

}  // namespace stiffsoft
