#include "io/scene_builder.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "libabd/mass_matrix.hpp"
#include "meshing/intersection.hpp"
#include "meshing/mass_moments.hpp"
#include "meshing/mesh_checks.hpp"
#include "meshing/read_surface_mesh.hpp"
#include "io/scene_schema.hpp"

namespace stiffsoft {

namespace {

Eigen::Matrix3d rotation(const Eigen::Vector3d& deg) {
  const Eigen::Vector3d r = deg * M_PI / 180.0;
  return (Eigen::AngleAxisd(r.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(r.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(r.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

SurfaceMesh body_mesh(const BodyDescription& body, const std::string& file, const std::string& path) {
  SurfaceMesh mesh;
  try {
    mesh = body.mesh.primitive ? make_primitive(*body.mesh.primitive) : read_surface_mesh(body.mesh.file);
  } catch (const std::exception& e) {
    throw SceneError(file, path + ".mesh", e.what());
  }
  mesh.V = mesh.V * body.scale.asDiagonal();
  if (const auto problem = closed_manifold_problem(mesh))
    throw SceneError(file, path + ".mesh", "body '" + body.name + "' needs a closed, manifold, outward-oriented surface: " + *problem);
  if (const auto faces = find_self_intersection(mesh))
    throw SceneError(file, path + ".mesh", "body '" + body.name + "' has a self-intersecting surface (faces " +
                                               std::to_string(faces->first) + " and " + std::to_string(faces->second) + ")");
  return mesh;
}

}  // namespace

const char* motion_name(Motion motion) {
  switch (motion) {
    case Motion::Dynamic: return "affine";
    case Motion::Fixed: return "fixed";
    case Motion::Kinematic: return "kinematic";
  }
  return "affine";
}

Model build_model(const SceneDescription& scene, const std::filesystem::path& file) {
  Model model;
  CollisionMesh& cm = model.mesh;
  std::vector<SurfaceMesh> world;
  std::vector<std::string> names;
  std::vector<Eigen::RowVector3d> x_bar_rows;
  std::vector<Eigen::RowVector3i> faces;
  std::vector<Eigen::RowVector2i> edge_rows;
  int vertex_offset = 0;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDescription& desc = scene.bodies[i];
    const std::string path = "bodies[" + std::to_string(i) + "]";
    SurfaceMesh mesh = body_mesh(desc, file.string(), path);
    const MassMoments moments = mass_moments(mesh);
    const Eigen::Vector3d c = moments.first / moments.volume;
    const Eigen::Matrix3d second_c = moments.second - moments.volume * c * c.transpose();
    const abd::MassProperties mp =
        abd::mass_properties(moments.volume, Eigen::Vector3d::Zero(), second_c, desc.density);

    BodyModel body;
    body.name = desc.name;
    body.motion = desc.kind == BodyKind::Fixed       ? Motion::Fixed
                  : desc.kind == BodyKind::Kinematic ? Motion::Kinematic
                                                     : Motion::Dynamic;
    if (body.motion != Motion::Fixed) {
      body.block = model.add_block(12);
      body.dof = model.blocks[body.block].offset;
    }
    body.M = abd::mass_matrix(mp);
    body.mass = mp.mass;
    body.volume = moments.volume;
    body.kappa = desc.kappa;
    const Eigen::Matrix3d R = rotation(desc.rotation_deg);
    body.q0 = abd::make_q(R * c + desc.position, R);
    body.v0 = desc.velocity;
    body.w0 = desc.angular_velocity;

    const Eigen::MatrixX2i E = edges(mesh.F);
    body.vertex_begin = vertex_offset;
    body.vertex_end = vertex_offset + int(mesh.V.rows());
    body.face_begin = int(faces.size());
    body.face_end = body.face_begin + int(mesh.F.rows());
    body.edge_begin = int(edge_rows.size());
    body.edge_end = body.edge_begin + int(E.rows());
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
      x_bar_rows.push_back(mesh.V.row(v) - c.transpose());
      cm.vertex_body.push_back(int(i));
      cm.vertex_node.push_back(-1);
    }
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      faces.push_back(mesh.F.row(f).array() + vertex_offset);
      cm.face_body.push_back(int(i));
    }
    for (Eigen::Index e = 0; e < E.rows(); ++e) {
      edge_rows.push_back(E.row(e).array() + vertex_offset);
      cm.edge_body.push_back(int(i));
    }
    vertex_offset = body.vertex_end;
    world.push_back({(mesh.V * R.transpose()).rowwise() + desc.position.transpose(), mesh.F});
    names.push_back(desc.name);
    model.bodies.push_back(std::move(body));
  }
  cm.x_bar.resize(x_bar_rows.size(), 3);
  for (size_t v = 0; v < x_bar_rows.size(); ++v) cm.x_bar.row(v) = x_bar_rows[v];
  cm.F.resize(faces.size(), 3);
  for (size_t f = 0; f < faces.size(); ++f) cm.F.row(f) = faces[f];
  cm.E.resize(edge_rows.size(), 2);
  for (size_t e = 0; e < edge_rows.size(); ++e) cm.E.row(e) = edge_rows[e];

  if (const auto overlap = find_overlap(world))
    throw SceneError(file.string(), "bodies",
                     "bodies must start apart (intersection-free), but " + describe(*overlap, names));
  return model;
}

void resolve_relative_defaults(SceneDescription& scene, const Model& model) {
  const double L = model.bounding_box_diagonal();
  if (!scene.contact.dhat) scene.contact.dhat = 1e-3 * L;
  if (!scene.contact.eps_v) scene.contact.eps_v = 1e-3 * L;
  if (!scene.solver.tolerance) scene.solver.tolerance = 1e-2 * L;
  if (!scene.output.frame_dt) scene.output.frame_dt = std::max(scene.time.dt, 1.0 / 60.0);
}

SimulationSettings simulation_settings(const SceneDescription& scene) {
  SimulationSettings s;
  s.h = scene.time.dt;
  s.integrator = scene.time.integrator;
  s.gravity = scene.gravity;
  s.dhat = scene.contact.dhat.value();
  s.mu = scene.contact.mu;
  s.eps_v = scene.contact.eps_v.value();
  s.kappa = scene.contact.kappa;
  s.tolerance = scene.solver.tolerance.value();
  s.max_iterations = scene.solver.max_iterations;
  s.linear_solver = scene.solver.linear;
  return s;
}

}  // namespace stiffsoft
