#include <stiffsoft/coupling/joints/joint_vectors.hpp>

#include <stdexcept>

#include <stiffsoft/libabd/affine_body.hpp>

namespace stiffsoft {

Eigen::Vector3d JointVector::value(const Eigen::VectorXd& q) const {
  if (block < 0) return constant;
  return constant + J * q.segment(dof, size);
}

namespace {
/// The end's body as a source of DOFs: −1 for the world and for fixed bodies.
int end_block(const Model& model, const JointEnd& end) {
  if (end.node >= 0) return model.nodes.block[end.node];
  return end.body < 0 ? -1 : model.bodies[end.body].block;
}
}  // namespace

JointVector end_point(const Model& model, const JointEnd& end, const Eigen::Vector3d& anchor) {
  JointVector v;
  v.block = end_block(model, end);
  if (end.node >= 0) {
    if (v.block < 0) {
      v.constant = model.nodes.X.row(end.node).transpose();
      return v;
    }
    v.dof = model.blocks[v.block].offset;
    v.size = 3;
    v.J = Eigen::Matrix3d::Identity();
    return v;
  }
  if (end.body < 0) {
    v.constant = anchor;
    return v;
  }
  if (v.block < 0) {
    v.constant = abd::world_point(model.bodies[end.body].q0, anchor);
    return v;
  }
  v.dof = model.blocks[v.block].offset;
  v.size = 12;
  v.J = abd::jacobian(anchor);
  return v;
}

JointVector end_direction(const Model& model, const JointEnd& end, const Eigen::Vector3d& w_bar) {
  if (end.node >= 0)
    throw std::invalid_argument("joint end on soft node " + std::to_string(end.node) +
                                ": a soft node carries no direction (only ball joints may attach to soft bodies)");
  JointVector v;
  v.block = end_block(model, end);
  if (end.body < 0) {
    v.constant = w_bar;
    return v;
  }
  if (v.block < 0) {
    v.constant = abd::affine_matrix(model.bodies[end.body].q0) * w_bar;
    return v;
  }
  v.dof = model.blocks[v.block].offset;
  v.size = 12;
  v.J = abd::jacobian(w_bar);
  v.J.leftCols<3>().setZero();  // A w̄ does not depend on p
  return v;
}

JointVectors::JointVectors(std::vector<JointVector> vectors) : m_vectors(std::move(vectors)) {
  const int rows = 3 * count();
  for (int k = 0; k < count(); ++k) {
    const JointVector& v = m_vectors[k];
    if (v.block < 0) continue;
    std::size_t s = 0;
    while (s < m_blocks.size() && m_blocks[s].block != v.block) ++s;
    if (s == m_blocks.size()) m_blocks.push_back({v.block, v.dof, Eigen::MatrixXd::Zero(rows, v.size)});
    m_blocks[s].G.middleRows(3 * k, 3) = v.J;
  }
}

Eigen::VectorXd JointVectors::gather(const Eigen::VectorXd& q) const {
  Eigen::VectorXd y(3 * count());
  for (int k = 0; k < count(); ++k) y.segment<3>(3 * k) = m_vectors[k].value(q);
  return y;
}

void JointVectors::scatter_gradient(const Eigen::VectorXd& g_y, Eigen::VectorXd& g) const {
  for (const Slot& s : m_blocks) g.segment(s.dof, s.G.cols()) += s.G.transpose() * g_y;
}

void JointVectors::scatter_hessian(const Eigen::MatrixXd& H_y, BlockHessian& H) const {
  for (const Slot& s : m_blocks) {
    const Eigen::MatrixXd HG = H_y * s.G;
    for (const Slot& t : m_blocks) {
      if (t.block > s.block) continue;
      H.add(t.block, s.block, t.G.transpose() * HG);
    }
  }
}

}  // namespace stiffsoft
