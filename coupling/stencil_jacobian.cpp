#include "coupling/stencil_jacobian.hpp"

namespace stiffsoft {

StencilJacobian::StencilJacobian(const Model& model, const std::array<int, 4>& vertices) {
  for (int i = 0; i < 4; ++i) {
    const int v = vertices[i];
    if (v < 0) continue;
    const int dof = model.bodies[model.mesh.vertex_body[v]].dof;
    if (dof < 0) continue;
    int s = 0;
    while (s < slots && block[s] != dof / 12) ++s;
    if (s == slots) block[slots++] = dof / 12;
    J.block<3, 12>(3 * i, 12 * s) = abd::jacobian(model.mesh.x_bar.row(v).transpose());
  }
}

void StencilJacobian::scatter_gradient(const Eigen::Matrix<double, 12, 1>& g_x,
                                       Eigen::VectorXd& g) const {
  for (int s = 0; s < slots; ++s)
    g.segment<12>(12 * block[s]) += J.middleCols<12>(12 * s).transpose() * g_x;
}

void StencilJacobian::scatter_hessian(const Eigen::Matrix<double, 12, 12>& H_x, BlockHessian& H) const {
  for (int s = 0; s < slots; ++s) {
    const Eigen::Matrix<double, 12, 12> HJ = H_x * J.middleCols<12>(12 * s);
    for (int t = 0; t < slots; ++t)
      if (block[t] <= block[s])
        H.add(block[t], block[s], J.middleCols<12>(12 * t).transpose() * HJ);
  }
}

}  // namespace stiffsoft
