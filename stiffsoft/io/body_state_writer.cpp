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

std::vector<BodyState> body_states(const Simulation& sim) {
  const Model& model = sim.model();
  const Eigen::MatrixX3d fc = sim.contact_forces(), ff = sim.friction_forces();
  const bool soft = model.has_soft_bodies();
  const Eigen::MatrixX3d nodes_x = soft ? sim.node_positions() : Eigen::MatrixX3d();
  const Eigen::MatrixX3d nodes_v = soft ? sim.node_velocities() : Eigen::MatrixX3d();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<BodyState> states(model.bodies.size());
  for (int b = 0; b < int(model.bodies.size()); ++b) {
    const BodyModel& body = model.bodies[b];
    BodyState& s = states[b];
    if (body.representation == Representation::Soft) {
      s.p.setZero();
      s.v.setZero();
      double mass = 0;
      for (int i = body.node_begin; i < body.node_end; ++i) {
        const double m = model.nodes.mass[i];
        s.p += m * nodes_x.row(i).transpose();
        s.v += m * nodes_v.row(i).transpose();
        s.kinetic_energy += 0.5 * m * nodes_v.row(i).squaredNorm();
        mass += m;
      }
      s.p /= mass;
      s.v /= mass;
      s.w.setConstant(nan);
      s.A.setConstant(nan);
    } else {
      const abd::Vector12d q = model.body_q(b, sim.q());
      abd::Vector12d qdot = abd::Vector12d::Zero();
      if (body.dof >= 0) qdot = sim.qdot().segment<12>(body.dof);
      s.p = abd::translation(q);
      s.A = abd::affine_matrix(q);
      s.v = qdot.head<3>();
      s.w = abd::angular_velocity(q, qdot);
      s.kinetic_energy = 0.5 * qdot.dot(body.M * qdot);
    }
    s.fc.setZero();
    s.ff.setZero();
    for (int vtx = body.vertex_begin; vtx < body.vertex_end; ++vtx) {
      s.fc += fc.row(vtx).transpose();
      s.ff += ff.row(vtx).transpose();
    }
  }
  return states;
}

std::vector<std::string> body_names(const Model& model) {
  std::vector<std::string> names;
  for (const BodyModel& body : model.bodies) names.push_back(body.name);
  return names;
}

void BodyStateWriter::add_state(int step, const Simulation& sim) {
  add_states(step, sim.time(), body_names(sim.model()), body_states(sim));
}

void BodyStateWriter::add_states(int step, double time, const std::vector<std::string>& names,
                                 const std::vector<BodyState>& states) {
  if (names.size() != states.size())
    throw std::invalid_argument("bodies.csv: " + std::to_string(names.size()) + " names for " +
                                std::to_string(states.size()) + " body states");
  std::string& rows = csv_.rows();
  for (std::size_t b = 0; b < states.size(); ++b) {
    const BodyState& s = states[b];
    rows += std::to_string(step);
    append_number(rows, time);
    rows += ',';
    if (names[b].find_first_of(",\"\r\n") == std::string::npos) {
      rows += names[b];
    } else {  // RFC 4180 quoting
      rows += '"';
      for (char c : names[b]) rows += c == '"' ? std::string("\"\"") : std::string(1, c);
      rows += '"';
    }
    for (int i = 0; i < 3; ++i) append_number(rows, s.p[i]);
    for (int i = 0; i < 3; ++i) append_number(rows, s.v[i]);
    for (int i = 0; i < 3; ++i) append_number(rows, s.w[i]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) append_number(rows, s.A(i, j));
    append_number(rows, s.kinetic_energy);
    for (int i = 0; i < 3; ++i) append_number(rows, s.fc[i]);
    for (int i = 0; i < 3; ++i) append_number(rows, s.ff[i]);
    rows += '\n';
  }
  csv_.added();
}

void BodyStateWriter::reload(const CsvEnd& end) { csv_.keep(end.length); }

void BodyStateWriter::flush() { csv_.flush(); }

}  // namespace stiffsoft
