#include "peers/peer_scene.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene_loader.hpp>
#include <stiffsoft/libabd/affine_body.hpp>
#include <stiffsoft/libabd/mass_matrix.hpp>
#include "peers/ring_links.hpp"

namespace stiffsoft::peers {

namespace {

/// Inertia about the centre of mass from the affine mass matrix: its a-blocks are
/// S = ρ∫x̄x̄ᵀ (x̄ centred at the centre of mass), and I = tr(S) I₃ − S.
Eigen::Matrix3d inertia_from_mass_matrix(const abd::Matrix12d& M) {
  abd::MassProperties mp;
  mp.mass = M(0, 0);
  mp.second = M.block<3, 3>(3, 3);
  return abd::inertia_tensor(mp);
}

}  // namespace

int PeerScene::dynamic_bodies() const {
  int count = 0;
  for (const PeerBody& b : bodies) count += b.fixed ? 0 : 1;
  return count;
}

bool is_convex(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const double tolerance = 1e-9 * diagonal;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    for (Eigen::Index v = 0; v < V.rows(); ++v)
      if (n.dot(V.row(v).transpose() - a) > tolerance) return false;
  }
  return true;
}

Eigen::MatrixX3d torus_slice(const PeerBody& body, int j) {
  const TorusFacets& t = body.torus.value();
  Eigen::MatrixX3d points(2 * t.m, 3);
  for (int ring = 0; ring < 2; ++ring)
    for (int k = 0; k < t.m; ++k) points.row(ring * t.m + k) = body.x_bar.row(((j + ring) % t.n) * t.m + k);
  return points;
}

bool torus_slices_are_convex(const PeerBody& body) {
  const TorusFacets& t = body.torus.value();
  if (body.x_bar.rows() != t.n * t.m || body.F.rows() != 2 * t.n * t.m) return false;
  const double tolerance = 1e-9 * body.x_bar.colwise().norm().maxCoeff();
  for (int j = 0; j < t.n; ++j) {
    const Eigen::MatrixX3d points = torus_slice(body, j);
    // stiffsoft/meshing/primitive.cpp writes slice j's quads (two triangles each) as faces [2jm, 2(j+1)m).
    for (int f = 2 * j * t.m; f < 2 * (j + 1) * t.m; ++f) {
      for (int corner = 0; corner < 3; ++corner) {
        const int ring = body.F(f, corner) / t.m;
        if (ring != j && ring != (j + 1) % t.n) return false;
      }
      const Eigen::Vector3d a = body.x_bar.row(body.F(f, 0)), b = body.x_bar.row(body.F(f, 1)),
                            c = body.x_bar.row(body.F(f, 2));
      const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
      for (Eigen::Index v = 0; v < points.rows(); ++v)
        if (n.dot(points.row(v).transpose() - a) > tolerance) return false;
    }
  }
  return true;
}

Eigen::MatrixX3d torus_centre_line(const PeerBody& body) {
  const TorusFacets& t = body.torus.value();
  Eigen::MatrixX3d line(t.n, 3);
  for (int j = 0; j < t.n; ++j) line.row(j) = body.x_bar.middleRows(j * t.m, t.m).colwise().mean();
  return line;
}

PeerScene load_peer_scene(const std::filesystem::path& file, double dt) {
  return make_peer_scene(load_scene(file), file, dt);
}

PeerScene make_peer_scene(SceneDescription description, const std::filesystem::path& file, double dt) {
  description.time.dt = dt;
  auto [resolved, model, settings] = prepare_scene(description, file.string());
  description = std::move(resolved);

  PeerScene scene;
  scene.name = description.name;
  scene.file = file;
  scene.dt = dt;
  scene.gravity = description.gravity;
  scene.mu = description.contact.mu;
  scene.dhat = description.contact.dhat.value();
  scene.settings = settings;
  scene.triangles = int(model.mesh.F.rows());

  double largest_footprint = 0;
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const BodyModel& m = model.bodies[i];
    const BodyDescription& d = description.bodies[i];
    if (m.motion == Motion::Kinematic)
      throw std::runtime_error(file.string() + ": body '" + m.name +
                               "' is kinematic; the peer benchmark supports affine and fixed bodies only");
    if (m.motion == Motion::Dynamic && m.dof < 0)
      throw std::runtime_error(file.string() + ": body '" + m.name +
                               "' has no affine DOFs (a soft body?); the peer benchmark supports rigid bodies only");
    PeerBody b;
    b.name = m.name;
    b.fixed = m.motion == Motion::Fixed;
    b.mass = m.mass;
    b.inertia = inertia_from_mass_matrix(m.M);
    b.x_bar = model.mesh.x_bar.middleRows(m.vertex_begin, m.vertex_end - m.vertex_begin);
    b.F = model.mesh.F.middleRows(m.face_begin, m.face_end - m.face_begin).array() - m.vertex_begin;
    b.first_face = m.face_begin;
    b.R0 = abd::affine_matrix(m.q0);
    b.c0 = abd::translation(m.q0);
    b.v0 = m.v0;
    b.w0 = m.w0;
    b.convex = is_convex(b.x_bar, b.F);
    const Eigen::Vector3d extent = b.x_bar.colwise().maxCoeff() - b.x_bar.colwise().minCoeff();
    b.thickness = extent.minCoeff();
    if (d.mesh.primitive) {
      const PrimitiveShape& p = *d.mesh.primitive;
      if (p.type == PrimitiveShape::Type::Box || p.type == PrimitiveShape::Type::Plane)
        b.box = Eigen::Vector3d(p.extents.cwiseProduct(d.scale));
      if (p.type == PrimitiveShape::Type::Torus) {
        b.torus = TorusFacets{p.resolution, std::max(3, p.resolution / 2), p.minor_radius};
        if (!torus_slices_are_convex(b))
          throw std::runtime_error(file.string() + ": body '" + b.name +
                                   "': its torus slices are not convex (mesh layout differs from stiffsoft/meshing/primitive.cpp?)");
        b.thickness = 2 * p.minor_radius * d.scale.minCoeff();
      }
    }
    if (b.fixed) {
      // World x–z footprint of the body's bounding box.
      const Eigen::MatrixX3d world = (b.x_bar * b.R0.transpose()).rowwise() + b.c0.transpose();
      const Eigen::Vector3d size = world.colwise().maxCoeff() - world.colwise().minCoeff();
      if (size.x() * size.z() > largest_footprint) {
        largest_footprint = size.x() * size.z();
        scene.ground = int(i);
      }
    }
    scene.bodies.push_back(std::move(b));
  }

  // Chain links: torus pairs whose centre lines are linked in the initial configuration.
  for (size_t i = 0; i < scene.bodies.size(); ++i)
    for (size_t j = i + 1; j < scene.bodies.size(); ++j) {
      const PeerBody &a = scene.bodies[i], &b = scene.bodies[j];
      if (!a.torus || !b.torus) continue;
      const Eigen::MatrixX3d la = (torus_centre_line(a) * a.R0.transpose()).rowwise() + a.c0.transpose();
      const Eigen::MatrixX3d lb = (torus_centre_line(b) * b.R0.transpose()).rowwise() + b.c0.transpose();
      if (linking_number(la, lb) != 0) scene.linked_rings.emplace_back(int(i), int(j));
    }
  scene.model = std::move(model);
  return scene;
}

}  // namespace stiffsoft::peers
