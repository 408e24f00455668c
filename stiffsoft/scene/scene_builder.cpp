#include <stiffsoft/scene/scene_builder.hpp>

#include <Eigen/Geometry>
#include <cmath>

#include <spdlog/spdlog.h>

#include <stiffsoft/scene/body_geometry.hpp>
#include <stiffsoft/scene/dirichlet_selection.hpp>
#include <stiffsoft/scene/model_choice.hpp>
#include <stiffsoft/libabd/mass_matrix.hpp>
#include <stiffsoft/libfem/lumped_mass.hpp>
#include <stiffsoft/meshing/tet_boundary.hpp>
#include <stiffsoft/meshing/intersection.hpp>
#include <stiffsoft/meshing/mass_moments.hpp>
#include <stiffsoft/meshing/mesh_checks.hpp>
#include <stiffsoft/meshing/read_surface_mesh.hpp>
#include <stiffsoft/scene/scene_schema.hpp>

namespace stiffsoft {

namespace {

Eigen::Matrix3d rotation(const Eigen::Vector3d& deg) {
  const Eigen::Vector3d r = deg * M_PI / 180.0;
  return (Eigen::AngleAxisd(r.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(r.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(r.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace

const char* motion_name(const BodyModel& body) {
  if (body.representation == Representation::Soft) return "soft";
  switch (body.motion) {
    case Motion::Dynamic: return "affine";
    case Motion::Fixed: return "fixed";
    case Motion::Kinematic: return "kinematic";
  }
  return "affine";
}

namespace {

/// Appends a body's surface to the collision mesh: rows of x_bar, triangles and edges (local
/// vertex indices), and the soft node of each vertex and tetrahedron of each triangle (both
/// empty for an affine body).
void append_surface(Model& model, int b, const Eigen::MatrixX3d& x_bar, const Eigen::MatrixX3i& F,
                    const std::vector<int>& vertex_node, const std::vector<int>& face_tet) {
  CollisionMesh& cm = model.mesh;
  BodyModel& body = model.bodies[b];
  const int offset = int(cm.x_bar.rows());
  const Eigen::MatrixX2i E = edges(F);
  body.vertex_begin = offset;
  body.vertex_end = offset + int(x_bar.rows());
  body.face_begin = int(cm.F.rows());
  body.face_end = body.face_begin + int(F.rows());
  body.edge_begin = int(cm.E.rows());
  body.edge_end = body.edge_begin + int(E.rows());
  cm.x_bar.conservativeResize(body.vertex_end, 3);
  cm.x_bar.bottomRows(x_bar.rows()) = x_bar;
  cm.F.conservativeResize(body.face_end, 3);
  cm.F.bottomRows(F.rows()) = F.array() + offset;
  cm.E.conservativeResize(body.edge_end, 2);
  cm.E.bottomRows(E.rows()) = E.array() + offset;
  for (Eigen::Index v = 0; v < x_bar.rows(); ++v) {
    cm.vertex_body.push_back(b);
    cm.vertex_node.push_back(vertex_node.empty() ? -1 : vertex_node[v]);
  }
  cm.face_body.insert(cm.face_body.end(), F.rows(), b);
  for (Eigen::Index f = 0; f < F.rows(); ++f) cm.face_tet.push_back(face_tet.empty() ? -1 : face_tet[f]);
  cm.edge_body.insert(cm.edge_body.end(), E.rows(), b);
}

/// An affine (or fixed, or kinematic) body from its closed surface; returns its world surface.
SurfaceMesh add_affine_body(Model& model, const BodyDescription& desc, const SurfaceMesh& mesh) {
  const MassMoments moments = mass_moments(mesh);
  const Eigen::Vector3d c = moments.first / moments.volume;
  const Eigen::Matrix3d second_c = moments.second - moments.volume * c * c.transpose();
  const abd::MassProperties mp = abd::mass_properties(moments.volume, Eigen::Vector3d::Zero(), second_c, desc.density);
  BodyModel body;
  body.name = desc.name;
  body.motion = desc.kind;
  if (body.motion != Motion::Fixed) {
    body.block = model.add_block(12);
    body.dof = model.blocks[body.block].offset;
  }
  body.M = abd::mass_matrix(mp);
  body.mass = mp.mass;
  body.volume = moments.volume;
  body.density = desc.density;
  body.kappa = desc.kappa;
  const Eigen::Matrix3d R = rotation(desc.rotation_deg);
  body.q0 = abd::make_q(R * c + desc.position, R);
  body.path = desc.path;
  body.v_after = desc.velocity;
  body.w_after = desc.angular_velocity;
  body.v0 = desc.path.empty() ? desc.velocity : desc.path.front().velocity;
  body.w0 = desc.path.empty() ? desc.angular_velocity : desc.path.front().angular_velocity;
  model.bodies.push_back(std::move(body));
  append_surface(model, int(model.bodies.size()) - 1, mesh.V.rowwise() - c.transpose(), mesh.F, {}, {});
  return {(mesh.V * R.transpose()).rowwise() + desc.position.transpose(), mesh.F};
}

/// A soft body from its tet mesh (body frame, scaled); returns its world surface.
SurfaceMesh add_soft_body(Model& model, const BodyDescription& desc, TetMesh mesh, const std::string& file,
                          const std::string& path) {
  const Eigen::Matrix3d R = rotation(desc.rotation_deg);
  mesh.X = (mesh.X * R.transpose()).rowwise() + desc.position.transpose();
  const int n = int(mesh.X.rows());
  std::vector<Motion> motion(n, Motion::Dynamic);
  Eigen::MatrixX3d velocity(n, 3);
  const Eigen::VectorXd mass = fem::lumped_mass(mesh.X, mesh.T, desc.density);
  const Eigen::Vector3d centre = (mesh.X.transpose() * mass) / mass.sum();
  for (int i = 0; i < n; ++i)
    velocity.row(i) = (desc.velocity + desc.angular_velocity.cross(mesh.X.row(i).transpose() - centre)).transpose();
  apply_dirichlet(mesh, desc.dirichlet, desc.name, file, path, motion, velocity);

  const int b = int(model.bodies.size());
  BodyModel body;
  body.name = desc.name;
  body.representation = Representation::Soft;
  body.mass = mass.sum();
  body.volume = tet_mesh_volume(mesh);
  body.density = desc.density;
  body.material = desc.material;
  body.v0 = desc.velocity;
  body.w0 = desc.angular_velocity;
  SoftNodes& nodes = model.nodes;
  body.node_begin = nodes.size();
  body.node_end = body.node_begin + n;
  body.tet_begin = int(nodes.T.rows());
  body.tet_end = body.tet_begin + int(mesh.T.rows());
  nodes.X.conservativeResize(body.node_end, 3);
  nodes.X.bottomRows(n) = mesh.X;
  nodes.velocity.conservativeResize(body.node_end, 3);
  nodes.velocity.bottomRows(n) = velocity;
  nodes.mass.conservativeResize(body.node_end);
  nodes.mass.tail(n) = mass;
  nodes.T.conservativeResize(body.tet_end, 4);
  nodes.T.bottomRows(mesh.T.rows()) = mesh.T.array() + body.node_begin;
  for (int i = 0; i < n; ++i) {
    nodes.motion.push_back(motion[i]);
    nodes.body.push_back(b);
    const int block = motion[i] == Motion::Fixed ? -1 : model.add_block(3);
    nodes.block.push_back(block);
    nodes.dof.push_back(block < 0 ? -1 : model.blocks[block].offset);
  }
  model.bodies.push_back(std::move(body));

  const TetBoundary boundary = boundary_surface(mesh, desc.name);
  std::vector<int> vertex_node(boundary.node_of_vertex.size());
  for (size_t v = 0; v < vertex_node.size(); ++v) vertex_node[v] = model.bodies[b].node_begin + boundary.node_of_vertex[v];
  std::vector<int> face_tet(boundary.tet_of_face.size());
  for (size_t f = 0; f < face_tet.size(); ++f) face_tet[f] = model.bodies[b].tet_begin + boundary.tet_of_face[f];
  append_surface(model, b, boundary.surface.V, boundary.surface.F, vertex_node, face_tet);
  return boundary.surface;
}

/// A unit vector perpendicular to the unit vector n.
Eigen::Vector3d perpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d other = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(other).normalized();
}

/// The joint end of a world point on body `b` (−1: the world) at the initial pose. A soft body
/// takes its node nearest to the point (the point becomes that node's position).
JointEnd joint_end(const Model& model, int b, Eigen::Vector3d& point, const Eigen::Vector3d& axis,
                   const Eigen::Vector3d& reference) {
  JointEnd end;
  end.body = b;
  if (b < 0) {
    end.anchor = point;
    end.axis = axis;
    end.reference = reference;
    return end;
  }
  const BodyModel& body = model.bodies[b];
  if (body.representation == Representation::Soft) {
    int best = body.node_begin;
    for (int i = body.node_begin; i < body.node_end; ++i)
      if ((model.nodes.X.row(i).transpose() - point).norm() < (model.nodes.X.row(best).transpose() - point).norm())
        best = i;
    end.node = best;
    point = model.nodes.X.row(best).transpose();
    return end;
  }
  const Eigen::Matrix3d A_inv = abd::affine_matrix(body.q0).inverse();
  end.anchor = A_inv * (point - abd::translation(body.q0));
  end.axis = A_inv * axis;
  end.reference = A_inv * reference;
  return end;
}

/// The default limit stiffness κ of a joint whose body a has mass m, size ℓ (bounding-box
/// diagonal) and initial speed v of its fastest point: m (|g| ℓ + ½ v²) (J), the energy scale
/// of lifting it by its own size plus its kinetic energy; 1 J when that is 0.
double automatic_limit_stiffness(double mass, double size, double speed, double gravity) {
  const double energy = mass * (gravity * size + 0.5 * speed * speed);
  return energy > 0 ? energy : 1.0;
}

/// The further nodes of soft body b within `radius` of `centre` (besides `primary`), each
/// pinned to body a's material point at the node's initial position.
std::vector<NodePin> node_pins(const Model& model, int a, int b, int primary, const Eigen::Vector3d& centre,
                               double radius) {
  const BodyModel& body_a = model.bodies[a];
  const Eigen::Matrix3d A_inv = abd::affine_matrix(body_a.q0).inverse();
  const Eigen::Vector3d p = abd::translation(body_a.q0);
  std::vector<NodePin> pins;
  for (int i = model.bodies[b].node_begin; i < model.bodies[b].node_end; ++i) {
    const Eigen::Vector3d X = model.nodes.X.row(i).transpose();
    if (i == primary || (X - centre).norm() > radius) continue;
    pins.push_back({i, A_inv * (X - p)});
  }
  return pins;
}

/// The model's joints from the scene's, at the initial pose (so equalities hold there).
void add_joints(Model& model, const SceneDescription& scene, const std::string& file) {
  const auto body_index = [&](const std::string& name) {
    for (int b = 0; b < int(model.bodies.size()); ++b)
      if (model.bodies[b].name == name) return b;
    return -1;
  };
  for (std::size_t i = 0; i < scene.joints.size(); ++i) {
    const JointDescription& desc = scene.joints[i];
    const std::string at = "joints[" + std::to_string(i) + "]";
    JointModel joint;
    joint.name = desc.name;
    joint.kind = desc.kind;
    const int a = body_index(desc.body_a), b = desc.body_b == "world" ? -1 : body_index(desc.body_b);
    const BodyModel& body_a = model.bodies[a];
    if (body_a.representation != Representation::Affine || body_a.motion == Motion::Fixed)
      throw SceneError(file, at + ".body_a",
                       "body \"" + body_a.name + "\" is " + motion_name(body_a) +
                           "; body_a must be an affine body that moves (dynamic or kinematic)");
    const bool soft_b = b >= 0 && model.bodies[b].representation == Representation::Soft;
    if (soft_b && desc.kind != JointKind::Ball)
      throw SceneError(file, at + ".body_b",
                       "body \"" + desc.body_b + "\" is soft; soft bodies take ball joints only (kind is " +
                           joint_kind_name(desc.kind) + ")");
    if (desc.nodes_within && !soft_b)
      throw SceneError(file, at + ".nodes_within",
                       "pins nodes of a soft body_b, but body_b \"" + desc.body_b + "\" is " +
                           (b < 0 ? std::string("the world") : motion_name(model.bodies[b])));
    if (soft_b && desc.damping > 0)
      throw SceneError(file, at + ".damping",
                       "a ball joint to soft body \"" + desc.body_b +
                           "\" cannot be damped: a soft node has no rotation to damp relative to (use 0)");
    const Eigen::Vector3d axis = desc.axis.normalized();
    const Eigen::Vector3d reference = perpendicular(axis);
    Eigen::Vector3d point_b = desc.anchor_b.value_or(desc.anchor);
    joint.b = joint_end(model, b, point_b, axis, reference);
    Eigen::Vector3d point_a = joint.b.node >= 0 ? point_b : desc.anchor;
    joint.a = joint_end(model, a, point_a, axis, reference);
    if (desc.nodes_within) {
      const double nearest = (point_b - desc.anchor).norm();
      if (nearest > *desc.nodes_within)
        throw SceneError(file, at + ".nodes_within",
                         "no node of body \"" + desc.body_b + "\" lies within " + std::to_string(*desc.nodes_within) +
                             " m of anchor (the nearest is " + std::to_string(nearest) + " m away)");
      joint.pins = node_pins(model, a, b, joint.b.node, desc.anchor, *desc.nodes_within);
    }
    const int n = body_a.vertex_end - body_a.vertex_begin;
    const auto x_bar = model.mesh.x_bar.middleRows(body_a.vertex_begin, n);
    const double size = (x_bar.colwise().maxCoeff() - x_bar.colwise().minCoeff()).norm();
    joint.axis_length = std::max(1e-3, size);
    joint.rest_length = (point_a - point_b).norm();
    joint.stiffness = desc.stiffness;
    joint.lower = desc.kind == JointKind::ConeTwist ? desc.twist_lower : desc.lower;
    joint.upper = desc.kind == JointKind::ConeTwist ? desc.twist_upper : desc.upper;
    joint.swing = desc.swing;
    const BodyDescription& scene_a = scene.bodies[a];
    const double speed = scene_a.velocity.norm() + scene_a.angular_velocity.norm() * size / 2;
    joint.limit_stiffness =
        desc.limit_stiffness.value_or(automatic_limit_stiffness(body_a.mass, size, speed, scene.gravity.norm()));
    joint.limit_activation = desc.limit_activation;
    joint.damping = desc.damping;
    if (desc.kind == JointKind::Distance && joint.rest_length <= 0)
      throw SceneError(file, at + ".anchor_b", "must differ from anchor (a distance joint keeps a positive length)");
    if (desc.kind == JointKind::BoundedDistance &&
        ((desc.lower && !(*desc.lower < joint.rest_length)) || (desc.upper && !(*desc.upper > joint.rest_length))))
      throw SceneError(file, at, "the initial distance " + std::to_string(joint.rest_length) +
                                     " m must lie strictly between lower and upper");
    model.joints.push_back(std::move(joint));
  }
}

/// The loads that decide `auto` bodies (model_choice.hpp), from every body's surface.
SceneLoads scene_loads(const SceneDescription& scene, const std::vector<SurfaceMesh>& surfaces) {
  SceneLoads loads;
  Eigen::Array3d lo = Eigen::Array3d::Constant(1e300), hi = Eigen::Array3d::Constant(-1e300);
  double fastest = 0;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDescription& desc = scene.bodies[i];
    const Eigen::Matrix3d R = rotation(desc.rotation_deg);
    const Eigen::MatrixX3d world = (surfaces[i].V * R.transpose()).rowwise() + desc.position.transpose();
    lo = lo.min(world.colwise().minCoeff().transpose().array());
    hi = hi.max(world.colwise().maxCoeff().transpose().array());
    if (desc.kind != Motion::Dynamic) continue;
    loads.weight += desc.density * mass_moments(surfaces[i]).volume * scene.gravity.norm();
    const double radius = (surfaces[i].V.colwise().maxCoeff() - surfaces[i].V.colwise().minCoeff()).norm() / 2;
    fastest = std::max(fastest, desc.velocity.norm() + desc.angular_velocity.norm() * radius);
  }
  const double g = scene.gravity.norm();
  const double height = g > 0 ? std::abs((hi - lo).matrix().dot(scene.gravity / g)) : 0.0;
  loads.fastest_speed = fastest + std::sqrt(2 * g * height);
  return loads;
}

/// Whether body i is simulated as a soft body; logs the choice of `auto` bodies.
bool is_soft(const SceneDescription& scene, size_t i, const SurfaceMesh& surface, const SceneLoads& loads) {
  const BodyDescription& desc = scene.bodies[i];
  if (desc.kind != Motion::Dynamic || desc.model == ModelChoice::Affine) return false;
  if (desc.model == ModelChoice::Soft) return true;
  const double strain = estimated_strain(loads, mass_moments(surface).volume, desc.density, desc.material.young);
  const bool affine = auto_is_affine(strain);
  spdlog::info("body '{}': model auto → {} (estimated strain {:.2g} {} {:.0e}: weight {:.3g} N, speed {:.3g} m/s)",
               desc.name, affine ? "affine" : "soft", strain, affine ? "<" : "≥", kAutoAffineStrain, loads.weight,
               loads.fastest_speed);
  return !affine;
}

}  // namespace

Model build_model(const SceneDescription& scene, const std::filesystem::path& file, const ElementLimits& limits) {
  std::vector<SurfaceMesh> surfaces;
  for (size_t i = 0; i < scene.bodies.size(); ++i)
    surfaces.push_back(body_surface(scene.bodies[i], limits, file.string(), "bodies[" + std::to_string(i) + "]"));
  const SceneLoads loads = scene_loads(scene, surfaces);

  Model model;
  std::vector<SurfaceMesh> world;
  std::vector<std::string> names;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDescription& desc = scene.bodies[i];
    const std::string path = "bodies[" + std::to_string(i) + "]";
    if (is_soft(scene, i, surfaces[i], loads)) {
      const double h = soft_mesh_size(desc, surfaces[i], file.string(), path);
      // Volume files were meshed (or read) for their surface already.
      if (desc.mesh.primitive || !is_volume_file(desc.mesh.file))
        check_tet_count(desc, mass_moments(surfaces[i]).volume, h, limits, file.string(), path);
      world.push_back(add_soft_body(model, desc, body_tet_mesh(desc, h, limits, file.string(), path), file.string(), path));
    } else {
      world.push_back(add_affine_body(model, desc, surfaces[i]));
    }
    names.push_back(desc.name);
  }
  if (const auto overlap = find_overlap(world))
    throw SceneError(file.string(), "bodies",
                     "bodies must start apart (intersection-free), but " + describe(*overlap, names));
  add_joints(model, scene, file.string());
  return model;
}

}  // namespace stiffsoft
