#include <stiffsoft/coupling/model/model.hpp>

#include <algorithm>

#include <stiffsoft/coupling/for_each_item.hpp>

namespace stiffsoft {

int Model::add_block(int size) {
  blocks.push_back({num_dofs, size});
  num_dofs += size;
  return int(blocks.size()) - 1;
}

abd::Vector12d Model::kinematic_q(int b, double t) const {
  const BodyModel& body = bodies[b];
  abd::Vector12d q = body.q0;
  for (const PathSegment& leg : body.path) {
    const double dt = std::min(t, leg.duration);
    q = abd::rigid_motion(q, leg.velocity, leg.angular_velocity, dt);
    t -= dt;
    if (t <= 0) return q;
  }
  return abd::rigid_motion(q, body.v_after, body.w_after, t);
}

Eigen::MatrixX3d Model::node_positions(const Eigen::VectorXd& q) const {
  Eigen::MatrixX3d x = nodes.X;
  for (int i = 0; i < nodes.size(); ++i)
    if (nodes.dof[i] >= 0) x.row(i) = q.segment<3>(nodes.dof[i]).transpose();
  return x;
}

namespace {
/// Calls f(b) for every body, in parallel by eight or more: each body writes only its own
/// vertices' rows.
template <class F>
void for_each_body(std::size_t bodies, const F& f) {
  for_each_item(bodies, 8, [&](std::size_t b) { f(int(b)); });
}

/// Rows [first, first + n) of x become A x̄ + p of the same rows of x̄, column by column (no
/// temporary), each entry summed as Eigen's product of x̄'s rows by Aᵀ sums it, then p added:
/// the numbers of (x̄ Aᵀ).rowwise() + p to the bit.
void map_rows(const Eigen::MatrixX3d& x_bar, Eigen::Index first, Eigen::Index n, const Eigen::Matrix3d& A,
              const Eigen::Vector3d& p, Eigen::MatrixX3d& x) {
  const double* u = x_bar.col(0).data() + first;
  const double* v = x_bar.col(1).data() + first;
  const double* w = x_bar.col(2).data() + first;
  for (int j = 0; j < 3; ++j) {
    double* out = x.col(j).data() + first;
    const double a = A(j, 0), b = A(j, 1), c = A(j, 2), t = p(j);
    for (Eigen::Index i = 0; i < n; ++i) out[i] = ((u[i] * a + v[i] * b) + w[i] * c) + t;
  }
}
}  // namespace

Eigen::MatrixX3d Model::surface(const Eigen::VectorXd& q) const {
  Eigen::MatrixX3d x(mesh.x_bar.rows(), 3);
  for_each_body(bodies.size(), [&](int b) {
    const BodyModel& body = bodies[b];
    if (body.representation == Representation::Soft) {
      for (int v = body.vertex_begin; v < body.vertex_end; ++v) {
        const int node = mesh.vertex_node[v];
        x.row(v) = nodes.dof[node] < 0 ? Eigen::RowVector3d(nodes.X.row(node))
                                       : Eigen::RowVector3d(q.segment<3>(nodes.dof[node]).transpose());
      }
      return;
    }
    const abd::Vector12d qb = body_q(b, q);
    map_rows(mesh.x_bar, body.vertex_begin, body.vertex_end - body.vertex_begin, abd::affine_matrix(qb),
             abd::translation(qb), x);
  });
  return x;
}

Eigen::MatrixX3d Model::surface_step(const Eigen::VectorXd& dq) const {
  Eigen::MatrixX3d dx(mesh.x_bar.rows(), 3);  // every row written below, body by body in parallel
  for_each_body(bodies.size(), [&](int b) {
    const BodyModel& body = bodies[b];
    if (body.representation == Representation::Soft) {
      for (int v = body.vertex_begin; v < body.vertex_end; ++v) {
        const int dof = nodes.dof[mesh.vertex_node[v]];
        dx.row(v) =
            dof >= 0 ? Eigen::RowVector3d(dq.segment<3>(dof).transpose()) : Eigen::RowVector3d::Zero();
      }
      return;
    }
    if (body.dof < 0) {
      dx.middleRows(body.vertex_begin, body.vertex_end - body.vertex_begin).setZero();
      return;
    }
    const abd::Vector12d d = dq.segment<12>(body.dof);
    map_rows(mesh.x_bar, body.vertex_begin, body.vertex_end - body.vertex_begin, abd::affine_matrix(d),
             abd::translation(d), dx);
  });
  return dx;
}

Eigen::VectorXd Model::initial_q() const {
  Eigen::VectorXd q(num_dofs);
  for (const BodyModel& body : bodies)
    if (body.dof >= 0) q.segment<12>(body.dof) = body.q0;
  for (int i = 0; i < nodes.size(); ++i)
    if (nodes.dof[i] >= 0) q.segment<3>(nodes.dof[i]) = nodes.X.row(i).transpose();
  return q;
}

Eigen::VectorXd Model::initial_qdot() const {
  Eigen::VectorXd qdot(num_dofs);
  for (const BodyModel& body : bodies)
    if (body.dof >= 0) qdot.segment<12>(body.dof) = abd::rigid_velocity(body.q0, body.v0, body.w0);
  for (int i = 0; i < nodes.size(); ++i)
    if (nodes.dof[i] >= 0) qdot.segment<3>(nodes.dof[i]) = nodes.velocity.row(i).transpose();
  return qdot;
}

double Model::bounding_box_diagonal() const {
  const Eigen::MatrixX3d x = surface(initial_q());
  if (x.rows() == 0) return 1.0;
  return (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm();
}

}  // namespace stiffsoft
