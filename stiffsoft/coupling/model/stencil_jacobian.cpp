#include <stiffsoft/coupling/model/stencil_jacobian.hpp>

namespace stiffsoft {

StencilJacobian::StencilJacobian(const Model& model, const std::array<int, 4>& vertices) {
  for (int i = 0; i < 4; ++i) {
    const int v = vertices[i];
    if (v < 0) continue;
    const int node = model.mesh.vertex_node[v];
    const int b = node < 0 ? model.bodies[model.mesh.vertex_body[v]].block : model.nodes.block[node];
    if (b < 0) continue;
    int s = 0;
    while (s < slots && block[s] != b) ++s;
    if (s == slots) {
      block[s] = b;
      offset[s] = model.blocks[b].offset;
      columns[s] = model.blocks[b].size;
      J[s].setZero();
      ++slots;
    }
    if (node < 0)
      J[s].middleRows<3>(3 * i) = abd::jacobian(model.mesh.x_bar.row(v).transpose());
    else
      J[s].block<3, 3>(3 * i, 0) = Eigen::Matrix3d::Identity();
  }
}

void StencilJacobian::scatter_gradient(const Eigen::Matrix<double, 12, 1>& g_x,
                                       Eigen::VectorXd& g) const {
  for (int s = 0; s < slots; ++s) {
    const Eigen::Matrix<double, 12, 1> g_s = J[s].transpose() * g_x;
    g.segment(offset[s], columns[s]) += g_s.head(columns[s]);
  }
}

void StencilJacobian::scatter_hessian(const Eigen::Matrix<double, 12, 12>& H_x, BlockHessian& H) const {
  for (int s = 0; s < slots; ++s) {
    const SlotMatrix HJ = H_x * J[s];
    for (int t = 0; t < slots; ++t) {
      if (block[t] > block[s]) continue;
      const SlotMatrix Hts = J[t].transpose() * HJ;
      H.add(block[t], block[s], Hts.topLeftCorner(columns[t], columns[s]));
    }
  }
}

}  // namespace stiffsoft
