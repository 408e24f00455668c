#include <stiffsoft/coupling/model/stencil_jacobian.hpp>

#include <stiffsoft/coupling/model/block_islands.hpp>

#include <stdexcept>

#include <stiffsoft/coupling/linear_solver/column_strips.hpp>

namespace stiffsoft {

namespace {
/// Position in an affine block's q = (p, a₁, a₂, a₃) of the entry that multiplies weight k in
/// component i: k = 0 is p_i, k ≥ 1 is A_{i,k−1} (row i of A is q[3 + 3i .. 3 + 3i + 2]).
/// A soft node's block has only k = 0, where this gives i as well.
constexpr int kDof[4][3] = {{0, 1, 2}, {3, 6, 9}, {4, 7, 10}, {5, 8, 11}};

/// Number of weights of a block with `columns` DOFs: 4 for an affine body, 1 for a soft node.
int weights(int columns) { return columns == 12 ? 4 : 1; }

/// Aᵀ B (12×12, column-major at `out`) on and above its diagonal, by strips of four columns
/// down to the diagonal: an affine body's diagonal block in 96 entries instead of 144. Entries
/// below the strips are left as they are.
template <int R>
void upper_product(const Eigen::Matrix<double, R, 12>& A, const Eigen::Matrix<double, R, 12>& B, double* out) {
  for_column_strips([&]<int C>() {
    Eigen::Map<Eigen::Matrix<double, 4 * C + 4, 4>, 0, Eigen::OuterStride<12>>(out + 48 * C) =
        A.template leftCols<4 * C + 4>().transpose().lazyProduct(B.template middleCols<4>(4 * C));
  });
}

/// Lays out the stencil's blocks in `out`: for every slot pair (t, s) with block[t] ≤ block[s],
/// fill(t, s, values) writes the columns[t] × columns[s] block J_tᵀ H J_s (column-major, q's
/// order) at `values`.
template <class Fill>
void for_block_pairs(const StencilJacobian& J, StencilHessian& out, Fill&& fill) {
  out.count = 0;
  int next = 0;
  for (int s = 0; s < J.slots; ++s) {
    for (int t = 0; t < J.slots; ++t) {
      if (J.block[t] > J.block[s]) continue;
      if (next + J.columns[t] * J.columns[s] > StencilHessian::kCapacity)
        throw std::logic_error("StencilJacobian: a stencil spans more DOFs than two affine bodies");
      fill(t, s, out.values.data() + next);
      out.row[out.count] = J.block[t];
      out.column[out.count] = J.block[s];
      out.at[out.count] = next;
      ++out.count;
      next += J.columns[t] * J.columns[s];
    }
  }
}
}  // namespace

StencilJacobian::StencilJacobian(const Model& model, const std::array<int, 4>& vertices) {
  for (int i = 0; i < 4; ++i) {
    const int v = vertices[i];
    if (v < 0) continue;
    const int node = model.mesh.vertex_node[v];
    const int b = vertex_block(model, v);
    if (b < 0) continue;
    int s = 0;
    while (s < slots && block[s] != b) ++s;
    if (s == slots) {
      block[s] = b;
      offset[s] = model.blocks[b].offset;
      columns[s] = model.blocks[b].size;
      ++slots;
    }
    slot_of[i] = s;
    w[i] << 1.0, (node < 0 ? Eigen::Vector3d(model.mesh.x_bar.row(v).transpose()) : Eigen::Vector3d::Zero());
  }
}

void StencilJacobian::scatter_gradient(const Eigen::Matrix<double, 12, 1>& g_x, Eigen::VectorXd& g,
                                       const BlockOwner& owner) const {
  for (int a = 0; a < 4; ++a) {
    const int s = slot_of[a];
    if (s < 0 || !owner.owns(block[s])) continue;
    for (int k = 0; k < weights(columns[s]); ++k)
      for (int i = 0; i < 3; ++i) g[offset[s] + kDof[k][i]] += w[a][k] * g_x[3 * a + i];
  }
}

Eigen::Matrix<double, 12, 1> StencilJacobian::step(const Eigen::VectorXd& dq) const {
  Eigen::Matrix<double, 12, 1> dx = Eigen::Matrix<double, 12, 1>::Zero();
  for (int a = 0; a < 4; ++a) {
    const int s = slot_of[a];
    if (s < 0) continue;
    for (int k = 0; k < weights(columns[s]); ++k)
      for (int i = 0; i < 3; ++i) dx[3 * a + i] += w[a][k] * dq[offset[s] + kDof[k][i]];
  }
  return dx;
}

void StencilJacobian::block_hessians(const Eigen::Matrix<double, 12, 12>& H_x, StencilHessian& out) const {
  for_block_pairs(*this, out, [&](int t, int s, double* block_ts) {
    const int nk = weights(columns[t]), nl = weights(columns[s]);
    // J_tᵀ H J_s = Σ over vertex pairs (a in t, b in s) of w_a w_bᵀ ⊗ H_ab, as K with rows
    // 3k + i and columns 3l + j: first G_b = Σ_a w_a ⊗ H_ab (12×3), then K += w_bᵀ ⊗ G_b.
    Eigen::Matrix<double, 12, 12> K = Eigen::Matrix<double, 12, 12>::Zero();
    for (int b = 0; b < 4; ++b) {
      if (slot_of[b] != s) continue;
      Eigen::Matrix<double, 12, 3> G = Eigen::Matrix<double, 12, 3>::Zero();
      for (int a = 0; a < 4; ++a) {
        if (slot_of[a] != t) continue;
        const Eigen::Matrix3d H_ab = H_x.block<3, 3>(3 * a, 3 * b);
        for (int k = 0; k < nk; ++k) G.block<3, 3>(3 * k, 0) += w[a][k] * H_ab;
      }
      for (int l = 0; l < nl; ++l) K.middleCols<3>(3 * l) += w[b][l] * G;
    }
    // K in q's order.
    for (int l = 0; l < nl; ++l)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < nk; ++k)
          for (int i = 0; i < 3; ++i) block_ts[kDof[l][j] * columns[t] + kDof[k][i]] = K(3 * k + i, 3 * l + j);
  });
}

template <int R>
void StencilJacobian::low_rank_block_hessians(const Eigen::Matrix<double, R, 12>& B, const Eigen::Matrix<double, R, R>& C,
                                              StencilHessian& out) const {
  // (B J)_s: the R × columns[s] rows of each slot, in q's order.
  std::array<Eigen::Matrix<double, R, 12>, 4> BJ;
  for (int s = 0; s < slots; ++s) BJ[s].setZero();
  for (int a = 0; a < 4; ++a) {
    const int s = slot_of[a];
    if (s < 0) continue;
    for (int k = 0; k < weights(columns[s]); ++k)
      for (int i = 0; i < 3; ++i) BJ[s].col(kDof[k][i]) += w[a][k] * B.col(3 * a + i);
  }
  std::array<Eigen::Matrix<double, R, 12>, 4> CBJ;  // C (B J)_s
  for (int s = 0; s < slots; ++s) CBJ[s] = C * BJ[s];
  // (B J)_tᵀ C (B J)_s at the block's fixed size: an affine body's 12 columns or a node's 3.
  const auto product = [&]<int Nt, int Ns>(int t, int s, double* block_ts) {
    Eigen::Map<Eigen::Matrix<double, Nt, Ns>> block(block_ts);
    block = BJ[t].template leftCols<Nt>().transpose().lazyProduct(CBJ[s].template leftCols<Ns>());
  };
  for_block_pairs(*this, out, [&](int t, int s, double* block_ts) {
    const int nt = columns[t], ns = columns[s];
    if (t == s && nt == 12) return upper_product<R>(BJ[t], CBJ[s], block_ts);
    if (nt == 12 && ns == 12) return product.template operator()<12, 12>(t, s, block_ts);
    if (nt == 12 && ns == 3) return product.template operator()<12, 3>(t, s, block_ts);
    if (nt == 3 && ns == 12) return product.template operator()<3, 12>(t, s, block_ts);
    if (nt == 3 && ns == 3) return product.template operator()<3, 3>(t, s, block_ts);
    Eigen::Map<Eigen::MatrixXd>(block_ts, nt, ns) = BJ[t].leftCols(nt).transpose().lazyProduct(CBJ[s].leftCols(ns));
  });
}

template void StencilJacobian::low_rank_block_hessians<1>(const Eigen::Matrix<double, 1, 12>&, const Eigen::Matrix<double, 1, 1>&,
                                                          StencilHessian&) const;
template void StencilJacobian::low_rank_block_hessians<2>(const Eigen::Matrix<double, 2, 12>&, const Eigen::Matrix<double, 2, 2>&,
                                                          StencilHessian&) const;
template void StencilJacobian::low_rank_block_hessians<3>(const Eigen::Matrix<double, 3, 12>&, const Eigen::Matrix<double, 3, 3>&,
                                                          StencilHessian&) const;
template void StencilJacobian::low_rank_block_hessians<4>(const Eigen::Matrix<double, 4, 12>&, const Eigen::Matrix<double, 4, 4>&,
                                                          StencilHessian&) const;
template void StencilJacobian::low_rank_block_hessians<5>(const Eigen::Matrix<double, 5, 12>&, const Eigen::Matrix<double, 5, 5>&,
                                                          StencilHessian&) const;

void StencilJacobian::scatter_hessian(const Eigen::Matrix<double, 12, 12>& H_x, BlockHessian& H) const {
  StencilHessian blocks;
  block_hessians(H_x, blocks);
  blocks.add_to(H);
}

void StencilHessian::add_to(BlockHessian& H) const {
  for (int k = 0; k < count; ++k) H.add_upper(row[k], column[k], values.data() + at[k]);
}

}  // namespace stiffsoft
