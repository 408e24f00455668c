#include <stiffsoft/io/body_state_writer.hpp>

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace stiffsoft {

namespace {

void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out += ',';
  out.append(buffer, result.ptr);
}

}  // namespace

const std::vector<std::string>& body_state_columns() {
  static const std::vector<std::string> columns{
      "step", "time", "body", "px", "py", "pz", "vx", "vy", "vz", "wx", "wy", "wz", "A00", "A01", "A02",
      "A10", "A11", "A12", "A20", "A21", "A22", "kinetic_energy", "fcx", "fcy", "fcz", "ffx", "ffy", "ffz"};
  return columns;
}

BodyStateWriter::BodyStateWriter(std::filesystem::path file, std::size_t pending_bytes)
    : csv_(std::move(file), body_state_columns(), pending_bytes) {}

void BodyStateWriter::add_state(int step, const Simulation& sim) {
  const Model& model = sim.model();
  const Eigen::MatrixX3d fc = sim.contact_forces(), ff = sim.friction_forces();
  const bool soft = model.has_soft_bodies();
  const Eigen::MatrixX3d nodes_x = soft ? sim.node_positions() : Eigen::MatrixX3d();
  const Eigen::MatrixX3d nodes_v = soft ? sim.node_velocities() : Eigen::MatrixX3d();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::string& rows = csv_.rows();
  for (int b = 0; b < int(model.bodies.size()); ++b) {
    const BodyModel& body = model.bodies[b];
    Eigen::Vector3d p, v, w;
    Eigen::Matrix3d A;
    double kinetic = 0;
    if (body.representation == Representation::Soft) {
      p.setZero();
      v.setZero();
      double mass = 0;
      for (int i = body.node_begin; i < body.node_end; ++i) {
        const double m = model.nodes.mass[i];
        p += m * nodes_x.row(i).transpose();
        v += m * nodes_v.row(i).transpose();
        kinetic += 0.5 * m * nodes_v.row(i).squaredNorm();
        mass += m;
      }
      p /= mass;
      v /= mass;
      w.setConstant(nan);
      A.setConstant(nan);
    } else {
      const abd::Vector12d q = model.body_q(b, sim.q());
      abd::Vector12d qdot = abd::Vector12d::Zero();
      if (body.dof >= 0) qdot = sim.qdot().segment<12>(body.dof);
      p = abd::translation(q);
      A = abd::affine_matrix(q);
      v = qdot.head<3>();
      w = abd::angular_velocity(q, qdot);
      kinetic = 0.5 * qdot.dot(body.M * qdot);
    }
    Eigen::Vector3d body_fc = Eigen::Vector3d::Zero(), body_ff = Eigen::Vector3d::Zero();
    for (int vtx = body.vertex_begin; vtx < body.vertex_end; ++vtx) {
      body_fc += fc.row(vtx).transpose();
      body_ff += ff.row(vtx).transpose();
    }
    rows += std::to_string(step);
    append_number(rows, sim.time());
    rows += ',';
    if (body.name.find_first_of(",\"\r\n") == std::string::npos) {
      rows += body.name;
    } else {  // RFC 4180 quoting
      rows += '"';
      for (char c : body.name) rows += c == '"' ? std::string("\"\"") : std::string(1, c);
      rows += '"';
    }
    for (int i = 0; i < 3; ++i) append_number(rows, p[i]);
    for (int i = 0; i < 3; ++i) append_number(rows, v[i]);
    for (int i = 0; i < 3; ++i) append_number(rows, w[i]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) append_number(rows, A(i, j));
    append_number(rows, kinetic);
    for (int i = 0; i < 3; ++i) append_number(rows, body_fc[i]);
    for (int i = 0; i < 3; ++i) append_number(rows, body_ff[i]);
    rows += '\n';
  }
  csv_.added();
}

void BodyStateWriter::reload(const CsvEnd& end) { csv_.keep(end.length); }

void BodyStateWriter::flush() { csv_.flush(); }

}  // namespace stiffsoft
