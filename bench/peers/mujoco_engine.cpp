#include "peers/mujoco_engine.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <utility>

namespace stiffsoft::peers {

namespace {

/// MuJoCo's constraint solvers' names, in mjtSolver's order.
const char* const kSolvers[] = {"PGS", "CG", "Newton"};

Eigen::Matrix3d matrix(const mjtNum* m) {
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = m[3 * r + c];
  return R;
}

}  // namespace

MujocoEngine::MujocoEngine(const PeerScene& scene, const MjcfSizes& sizes, std::string name,
                           const std::string& solver)
    : m_name(std::move(name)), m_sizes(sizes) {
  const auto* const named = std::find(std::begin(kSolvers), std::end(kSolvers), solver);
  if (!solver.empty() && named == std::end(kSolvers))
    throw std::invalid_argument("MuJoCo solver '" + solver + "': expected PGS, CG or Newton");
  const std::string xml = make_mjcf(scene, sizes);
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* file = "scene.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), file, int(xml.size())) != 0)
    throw std::runtime_error("MuJoCo: cannot make the in-memory file for the MJCF text");
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), file)], xml.data(), xml.size());
  char error[1024] = "";
  m_model = mj_loadXML(file, vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!m_model) throw std::runtime_error(scene.file.string() + ": MuJoCo rejects the generated MJCF: " + error);
  if (!solver.empty()) m_model->opt.solver = int(named - std::begin(kSolvers));
  m_data = mj_makeData(m_model);
  if (!m_data) throw std::runtime_error(scene.file.string() + ": MuJoCo cannot allocate mjData (njmax = " +
                                        std::to_string(sizes.njmax) + ")");

  m_geom_owner.resize(size_t(m_model->ngeom));
  for (int g = 0; g < m_model->ngeom; ++g) m_geom_owner[size_t(g)] = body_of_geom_name(m_model->names + m_model->name_geomadr[g]);
  m_body.assign(scene.bodies.size(), 0);
  if (scene.ground >= 0 && ground_is_plane(scene, scene.ground)) m_plane = scene.ground;
  m_fixed.resize(scene.bodies.size());
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const PeerBody& body = scene.bodies[i];
    if (body.fixed) {
      m_fixed[i] = {body.R0, body.c0};
      continue;
    }
    std::string name = "b";  // appended, not "b" + …: GCC 12 warns falsely (-Wrestrict) on that
    name += std::to_string(i);
    const int id = mj_name2id(m_model, mjOBJ_BODY, name.c_str());
    if (id < 0) throw std::logic_error("MuJoCo model lacks body " + name);
    m_body[i] = id;
    // Free joint: qvel = (linear velocity, world frame; angular velocity, body frame).
    const int dof = m_model->jnt_dofadr[m_model->body_jntadr[id]];
    const Eigen::Vector3d w_local = body.R0.transpose() * body.w0;
    for (int d = 0; d < 3; ++d) {
      m_data->qvel[dof + d] = body.v0[d];
      m_data->qvel[dof + 3 + d] = w_local[d];
    }
  }
  mj_forward(m_model, m_data);
}

MujocoEngine::~MujocoEngine() {
  if (m_data) mj_deleteData(m_data);
  if (m_model) mj_deleteModel(m_model);
}

std::string MujocoEngine::settings() const {
  const mjOption& o = m_model->opt;
  static const char* integrators[] = {"Euler (semi-implicit)", "RK4", "implicit"};
  static const char* cones[] = {"pyramidal", "elliptic"};
  static const char* jacobians[] = {"dense", "sparse", "auto"};
  const mjtNum* ref = m_model->geom_solref;
  const mjtNum* imp = m_model->geom_solimp;
  char line[768];
  std::snprintf(
      line, sizeof line,
      "MuJoCo %s, %s integrator, %s solver, %d iterations, tolerance %.3g, %s cone, noslip %d it., "
      "impratio %.3g, %s Jacobian, contacts solref (%.3g, %.3g) solimp (%.3g, %.3g, %.3g), margin 0, "
      "condim 3, MPR %d it. tol. %.3g; %d geoms, %d meshes; buffers nconmax %d, njmax %d",
      mj_versionString(), integrators[o.integrator], kSolvers[o.solver], o.iterations, o.tolerance,
      cones[o.cone], o.noslip_iterations, o.impratio, jacobians[o.jacobian], ref[0], ref[1], imp[0], imp[1],
      imp[2], o.mpr_iterations, o.mpr_tolerance, m_model->ngeom, m_model->nmesh, m_sizes.nconmax,
      m_sizes.njmax);
  return line;
}

void MujocoEngine::step() {
  mj_step(m_model, m_data);
  m_stale = true;
  if (m_data->ncon > m_peak_contacts) m_peak_contacts = m_data->ncon;
  if (m_data->nefc > m_peak_rows) m_peak_rows = m_data->nefc;
}

std::vector<Penetration> MujocoEngine::penetrations() {
  std::vector<Penetration> out;
  for (int i = 0; i < m_data->ncon; ++i) {
    const mjContact& c = m_data->contact[i];
    if (c.dist < 0)
      out.push_back({m_geom_owner[size_t(c.geom1)], m_geom_owner[size_t(c.geom2)], -c.dist, -c.dist});
  }
  return out;
}

void MujocoEngine::finish_probe() {
  mj_forward(m_model, m_data);
  m_stale = false;
}

void MujocoEngine::refresh() const {
  if (!m_stale) return;
  mj_kinematics(m_model, m_data);
  m_stale = false;
}

Pose MujocoEngine::pose(int b) const {
  refresh();
  if (m_body[size_t(b)] == 0) return m_fixed[size_t(b)];
  const int id = m_body[size_t(b)];
  return {matrix(m_data->xmat + 9 * id), Eigen::Vector3d(m_data->xpos[3 * id], m_data->xpos[3 * id + 1],
                                                         m_data->xpos[3 * id + 2])};
}

Twist MujocoEngine::twist(int b) const {
  refresh();
  const int id = m_body[size_t(b)];
  if (id == 0) return {};
  const int dof = m_model->jnt_dofadr[m_model->body_jntadr[id]];
  const mjtNum* qvel = m_data->qvel + dof;
  return {Eigen::Vector3d(qvel[0], qvel[1], qvel[2]),
          matrix(m_data->xmat + 9 * id) * Eigen::Vector3d(qvel[3], qvel[4], qvel[5])};
}

Eigen::MatrixX3d MujocoEngine::collision_vertices(int b) const {
  refresh();
  std::vector<Eigen::Vector3d> points;
  for (int g = 0; g < m_model->ngeom; ++g) {
    if (m_geom_owner[size_t(g)] != b) continue;
    const Eigen::Matrix3d R = matrix(m_data->geom_xmat + 9 * g);
    const Eigen::Vector3d p(m_data->geom_xpos[3 * g], m_data->geom_xpos[3 * g + 1], m_data->geom_xpos[3 * g + 2]);
    if (m_model->geom_type[g] == mjGEOM_PLANE) {
      // The ground's top face: the plane's rectangle (it collides as a half-space).
      const mjtNum* s = m_model->geom_size + 3 * g;
      for (int i = 0; i < 4; ++i) points.push_back(R * Eigen::Vector3d((i & 1) ? s[0] : -s[0], (i & 2) ? s[1] : -s[1], 0) + p);
    } else if (m_model->geom_type[g] == mjGEOM_BOX) {
      const mjtNum* s = m_model->geom_size + 3 * g;
      for (int i = 0; i < 8; ++i)
        points.push_back(R * Eigen::Vector3d((i & 1) ? s[0] : -s[0], (i & 2) ? s[1] : -s[1], (i & 4) ? s[2] : -s[2]) + p);
    } else if (m_model->geom_type[g] == mjGEOM_MESH) {
      const int mesh = m_model->geom_dataid[g];
      const float* v = m_model->mesh_vert + 3 * m_model->mesh_vertadr[mesh];
      for (int i = 0; i < m_model->mesh_vertnum[mesh]; ++i)
        points.push_back(R * Eigen::Vector3d(v[3 * i], v[3 * i + 1], v[3 * i + 2]) + p);
    }
  }
  Eigen::MatrixX3d world(Eigen::Index(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) world.row(Eigen::Index(i)) = points[i].transpose();
  return world;
}

std::string MujocoEngine::statistics() const {
  return "peak " + std::to_string(m_peak_contacts) + " contacts (nconmax " + std::to_string(m_sizes.nconmax) + "), " +
         std::to_string(m_peak_rows) + " constraint rows (njmax " + std::to_string(m_sizes.njmax) + ")";
}

std::string MujocoEngine::warnings() const {
  std::string out;
  const struct {
    int id;
    const char* what;
  } kinds[] = {{mjWARN_CONTACTFULL, "contact buffer full"}, {mjWARN_CNSTRFULL, "constraint buffer full"},
               {mjWARN_BADQACC, "bad qacc (state reset)"}, {mjWARN_BADQPOS, "bad qpos"},
               {mjWARN_BADQVEL, "bad qvel"}, {mjWARN_INERTIA, "singular inertia"}};
  for (const auto& k : kinds)
    if (m_data->warning[k.id].number > 0)
      out += (out.empty() ? "" : "; ") + std::string(k.what) + " x" + std::to_string(m_data->warning[k.id].number);
  return out;
}

}  // namespace stiffsoft::peers
