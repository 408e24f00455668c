#include <stiffsoft/io/simulation_frame.hpp>

#include <stiffsoft/scene/scene_builder.hpp>

namespace stiffsoft {

namespace {

/// A soft body's frame: all its nodes as points, tets then surface triangles as cells; surface
/// forces land on their nodes; triangles carry their tetrahedron's von Mises stress.
BodyFrame soft_frame(const Simulation& sim, const BodyModel& body, const Eigen::MatrixX3d& fc,
                     const Eigen::MatrixX3d& ff, const Eigen::MatrixX3d& nodes_x, const Eigen::MatrixX3d& nodes_v,
                     const Eigen::VectorXd& von_mises) {
  const Model& model = sim.model();
  const int n = body.node_end - body.node_begin, nt = body.tet_end - body.tet_begin,
            nf = body.face_end - body.face_begin;
  BodyFrame f;
  f.x = nodes_x.middleRows(body.node_begin, n);
  f.velocity = nodes_v.middleRows(body.node_begin, n);
  f.displacement = f.x - model.nodes.X.middleRows(body.node_begin, n);
  f.T = model.nodes.T.middleRows(body.tet_begin, nt).array() - body.node_begin;
  f.F.resize(nf, 3);
  f.von_mises.resize(nt + nf);
  f.von_mises.head(nt) = von_mises.segment(body.tet_begin, nt);
  for (int k = 0; k < nf; ++k) {
    const int face = body.face_begin + k;
    for (int j = 0; j < 3; ++j) f.F(k, j) = model.mesh.vertex_node[model.mesh.F(face, j)] - body.node_begin;
    f.von_mises[nt + k] = von_mises[model.mesh.face_tet[face]];
  }
  f.contact_force = Eigen::MatrixX3d::Zero(n, 3);
  f.friction_force = Eigen::MatrixX3d::Zero(n, 3);
  for (int v = body.vertex_begin; v < body.vertex_end; ++v) {
    const int node = model.mesh.vertex_node[v] - body.node_begin;
    f.contact_force.row(node) = fc.row(v);
    f.friction_force.row(node) = ff.row(v);
  }
  return f;
}

}  // namespace

std::vector<BodyFrame> body_frames(const Simulation& sim, const Eigen::MatrixX3d& x0) {
  const Model& model = sim.model();
  const Eigen::MatrixX3d x = sim.surface(), v = sim.surface_velocity(), fc = sim.contact_forces(),
                         ff = sim.friction_forces();
  const bool soft = model.has_soft_bodies();
  const Eigen::MatrixX3d nodes_x = soft ? sim.node_positions() : Eigen::MatrixX3d();
  const Eigen::MatrixX3d nodes_v = soft ? sim.node_velocities() : Eigen::MatrixX3d();
  const Eigen::VectorXd von_mises = soft ? sim.von_mises() : Eigen::VectorXd();
  std::vector<BodyFrame> frames;
  for (const BodyModel& body : model.bodies) {
    BodyFrame f;
    if (body.representation == Representation::Soft) {
      f = soft_frame(sim, body, fc, ff, nodes_x, nodes_v, von_mises);
    } else {
      const int n = body.vertex_end - body.vertex_begin, nf = body.face_end - body.face_begin;
      f.x = x.middleRows(body.vertex_begin, n);
      f.F = model.mesh.F.middleRows(body.face_begin, nf).array() - body.vertex_begin;
      f.velocity = v.middleRows(body.vertex_begin, n);
      f.displacement = f.x - x0.middleRows(body.vertex_begin, n);
      f.contact_force = fc.middleRows(body.vertex_begin, n);
      f.friction_force = ff.middleRows(body.vertex_begin, n);
    }
    f.name = body.name;
    f.model = motion_name(body);
    frames.push_back(std::move(f));
  }
  return frames;
}


std::vector<JointFrameEntry> joint_frame_entries(const Simulation& sim) {
  const std::vector<Eigen::Vector3d> x_a = sim.joint_positions(), x_b = sim.joint_positions_b();
  const std::vector<Eigen::Vector3d>& f = sim.joint_forces();
  const std::vector<double> gaps = sim.joint_gaps();
  std::vector<JointFrameEntry> out;
  for (std::size_t j = 0; j < x_a.size(); ++j) {
    const JointModel& joint = sim.model().joints[j];
    out.push_back({joint.name, int(joint.kind), x_a[j], x_b[j], j < f.size() ? f[j] : Eigen::Vector3d::Zero(), gaps[j]});
  }
  return out;
}

}  // namespace stiffsoft
