#include "peers/mjcf.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>

namespace stiffsoft::peers {

namespace {

std::string numbers(const double* v, int n) {
  std::string out;
  char buffer[32];
  for (int i = 0; i < n; ++i) {
    std::snprintf(buffer, sizeof buffer, i ? " %.17g" : "%.17g", v[i]);
    out += buffer;
  }
  return out;
}

std::string vec(const Eigen::Vector3d& v) { return numbers(v.data(), 3); }

/// MuJoCo quaternion (w, x, y, z) of a rotation.
std::string quat(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  const double wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
  return numbers(wxyz, 4);
}

/// Registers a mesh asset of the points (rows) once and returns its name.
class MeshAssets {
 public:
  std::string add(const Eigen::MatrixX3d& points) {
    std::string key(reinterpret_cast<const char*>(points.data()), sizeof(double) * size_t(points.size()));
    auto it = m_names.find(key);
    if (it != m_names.end()) return it->second;
    std::string name = "m";
    name += std::to_string(m_names.size());
    m_xml << "    <mesh name=\"" << name << "\" vertex=\"";
    for (Eigen::Index v = 0; v < points.rows(); ++v) {
      const Eigen::Vector3d p = points.row(v).transpose();
      m_xml << (v ? " " : "") << vec(p);
    }
    m_xml << "\"/>\n";
    m_names.emplace(std::move(key), name);
    return name;
  }
  std::string xml() const { return m_xml.str(); }

 private:
  std::map<std::string, std::string> m_names;
  std::ostringstream m_xml;
};

}  // namespace

bool ground_is_plane(const PeerScene& scene, int body) {
  if (body != scene.ground || !scene.bodies[size_t(body)].box) return false;
  const Eigen::Vector3d up = -scene.gravity.normalized();
  return (scene.bodies[size_t(body)].R0.col(1) - up).norm() < 1e-9;
}

int body_of_geom_name(const char* name) {
  if (!name || name[0] != 'b') return -1;
  char* end = nullptr;
  const long index = std::strtol(name + 1, &end, 10);
  return end && *end == '_' ? int(index) : -1;
}

std::string make_mjcf(const PeerScene& scene, const MjcfSizes& sizes) {
  MeshAssets assets;
  std::ostringstream world;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const PeerBody& body = scene.bodies[i];
    std::string tag = "b";
    tag += std::to_string(i);
    // The body's geoms, in the body frame (x̄, centred at the centre of mass).
    std::vector<std::string> geoms;
    if (ground_is_plane(scene, int(i))) {
      // A plane through the top face (MuJoCo's plane normal is its local z; turn it to the body's y).
      const Eigen::Matrix3d R = body.R0 * Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
      const Eigen::Vector3d top = body.c0 + body.R0 * Eigen::Vector3d(0, 0.5 * body.box->y(), 0);
      const Eigen::Vector3d size(0.5 * body.box->x(), 0.5 * body.box->z(), 1.0);
      world << "    <geom name=\"" << tag << "_0\" type=\"plane\" size=\"" << vec(size) << "\" pos=\"" << vec(top)
            << "\" quat=\"" << quat(R) << "\"/>\n";
      continue;
    }
    if (body.fixed && body.box) {
      geoms.push_back("type=\"box\" size=\"" + vec(0.5 * *body.box) + "\"");
    } else if (body.convex) {
      geoms.push_back("type=\"mesh\" mesh=\"" + assets.add(body.x_bar) + "\"");
    } else if (body.torus) {
      for (int j = 0; j < body.torus->n; ++j)
        geoms.push_back("type=\"mesh\" mesh=\"" + assets.add(torus_slice(body, j)) + "\"");
    } else {
      throw std::runtime_error(scene.file.string() + ": body '" + body.name +
                               "' is not convex and not a torus primitive: the MuJoCo scene has no decomposition for it");
    }
    if (body.fixed) {
      // World-body geoms: the body's pose goes on each geom.
      for (size_t k = 0; k < geoms.size(); ++k)
        world << "    <geom name=\"" << tag << "_" << k << "\" " << geoms[k] << " pos=\"" << vec(body.c0)
              << "\" quat=\"" << quat(body.R0) << "\"/>\n";
      continue;
    }
    const Eigen::Matrix3d& I = body.inertia;
    const double full[6] = {I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)};
    world << "    <body name=\"" << tag << "\" pos=\"" << vec(body.c0) << "\" quat=\"" << quat(body.R0) << "\">\n"
          << "      <freejoint/>\n"
          << "      <inertial pos=\"0 0 0\" mass=\"" << numbers(&body.mass, 1) << "\" fullinertia=\""
          << numbers(full, 6) << "\"/>\n";
    for (size_t k = 0; k < geoms.size(); ++k)
      world << "      <geom name=\"" << tag << "_" << k << "\" " << geoms[k] << "/>\n";
    world << "    </body>\n";
  }

  std::ostringstream xml;
  xml << "<mujoco model=\"" << scene.name << "\">\n"
      << "  <option timestep=\"" << numbers(&scene.dt, 1) << "\" gravity=\"" << vec(scene.gravity) << "\"/>\n"
      << "  <size nconmax=\"" << sizes.nconmax << "\" njmax=\"" << sizes.njmax << "\"/>\n"
      << "  <default>\n    <geom friction=\"" << numbers(&scene.mu, 1) << " 0.005 0.0001\"/>\n  </default>\n"
      << "  <asset>\n"
      << assets.xml() << "  </asset>\n"
      << "  <worldbody>\n"
      << world.str() << "  </worldbody>\n"
      << "</mujoco>\n";
  return xml.str();
}

}  // namespace stiffsoft::peers
