#include <stiffsoft/io/frame_writer.hpp>

#include <vtkCellType.h>

#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include <stiffsoft/io/atomic_file.hpp>
#include <stiffsoft/io/vtu_text.hpp>

namespace stiffsoft {

namespace {

/// Shortest text that reads back to exactly the same double.
std::string format_double(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, result.ptr);
}

/// Escapes the five XML special characters for use inside a double-quoted attribute.
std::string xml_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string frame_stem(const std::string& scene, int frame) {
  char number[16];
  std::snprintf(number, sizeof(number), "%06d", frame);
  return scene + "_" + number;
}

void check_shapes(const BodyFrame& body) {
  const Eigen::Index n = body.x.rows();
  const auto check_per_vertex = [&](const Eigen::MatrixX3d& a, const char* what) {
    if (a.size() != 0 && a.rows() != n) {
      throw std::invalid_argument("body '" + body.name + "': " + what + " has " +
                                  std::to_string(a.rows()) + " rows, expected 0 or |V| = " +
                                  std::to_string(n));
    }
  };
  check_per_vertex(body.velocity, "velocity");
  check_per_vertex(body.displacement, "displacement");
  check_per_vertex(body.contact_force, "contact_force");
  check_per_vertex(body.friction_force, "friction_force");
  if (body.F.size() != 0 && (body.F.minCoeff() < 0 || body.F.maxCoeff() >= n)) {
    throw std::invalid_argument("body '" + body.name + "': face indices must lie in [0, " +
                                std::to_string(n) + ")");
  }
  if (body.T.size() != 0 && (body.T.minCoeff() < 0 || body.T.maxCoeff() >= n)) {
    throw std::invalid_argument("body '" + body.name + "': tetrahedron indices must lie in [0, " +
                                std::to_string(n) + ")");
  }
  const Eigen::Index cells = body.T.rows() + body.F.rows();
  if (body.von_mises.size() != 0 && body.von_mises.size() != cells) {
    throw std::invalid_argument("body '" + body.name + "': von_mises has " + std::to_string(body.von_mises.size()) +
                                " values, expected 0 or |T| + |F| = " + std::to_string(cells));
  }
}

/// |V|×3 Eigen (column-major) → x, y, z of each row in turn; zeros when `a` is empty.
std::vector<double> row_major(const Eigen::MatrixX3d& a, Eigen::Index n) {
  std::vector<double> out(std::size_t(3 * n), 0.0);
  if (a.size() == 0) return out;
  for (Eigen::Index i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) out[std::size_t(3 * i + k)] = a(i, k);
  return out;
}

/// The body's .vtu: tetrahedra, then triangles; point, cell and field data.
std::string vtu_text(double time, const BodyFrame& body) {
  const Eigen::Index n = body.x.rows(), nt = body.T.rows(), m = body.F.rows();
  VtuText vtu(n, nt + m);
  vtu.add_field("time", time);
  vtu.add_field("body", body.name);
  vtu.add_field("model", body.model);
  for (const auto& [array, name] : {std::pair{&body.velocity, "velocity"}, {&body.displacement, "displacement"},
                                    {&body.contact_force, "contact_force"}, {&body.friction_force, "friction_force"}})
    vtu.add_point_vectors(name, row_major(*array, n).data());
  if (body.von_mises.size() != 0) vtu.add_cell_scalars("von_mises", body.von_mises.data());
  vtu.set_points(row_major(body.x, n).data());
  std::vector<std::int64_t> connectivity;
  connectivity.reserve(std::size_t(4 * nt + 3 * m));
  std::vector<std::int64_t> ends;
  ends.reserve(std::size_t(nt + m));
  std::vector<std::uint8_t> types(std::size_t(nt), VTK_TETRA);
  types.resize(std::size_t(nt + m), VTK_TRIANGLE);
  for (Eigen::Index t = 0; t < nt; ++t) {
    for (int k = 0; k < 4; ++k) connectivity.push_back(body.T(t, k));
    ends.push_back(std::int64_t(connectivity.size()));
  }
  for (Eigen::Index f = 0; f < m; ++f) {
    for (int k = 0; k < 3; ++k) connectivity.push_back(body.F(f, k));
    ends.push_back(std::int64_t(connectivity.size()));
  }
  vtu.set_cells(connectivity.data(), ends.data(), types.data());
  return vtu.str();
}

/// Serializes into memory, then writes atomically, so a partial .vtu never exists under its
/// final name and I/O errors surface in one place.
void write_vtu(const std::filesystem::path& path, double time, const BodyFrame& body) {
  const std::string text = vtu_text(time, body);
  write_file_atomically(path, [&](std::ostream& out) { out.write(text.data(), std::streamsize(text.size())); });
}

}  // namespace

std::string sanitize_file_name(const std::string& name) {
  if (name.empty()) return "body";
  std::string out = name;
  for (char& c : out) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '-' || c == '_' || c == '.';
    if (!keep) c = '_';
  }
  return out;
}

FrameWriter::FrameWriter(std::filesystem::path out_dir, std::string scene_name)
    : out_dir_(std::move(out_dir)), scene_name_(std::move(scene_name)) {
  if (scene_name_.empty() || scene_name_.find('/') != std::string::npos) {
    throw std::invalid_argument("scene name '" + scene_name_ +
                                "' cannot name output files (empty or contains '/')");
  }
  std::error_code ec;
  std::filesystem::create_directories(out_dir_ / "frames", ec);
  if (ec) {
    throw std::runtime_error("cannot create output folder '" + (out_dir_ / "frames").string() +
                             "': " + ec.message());
  }
  write_pvd();
}

void FrameWriter::write(double time, const std::vector<BodyFrame>& bodies) {
  for (const BodyFrame& body : bodies) check_shapes(body);

  const int frame = frame_count();
  const std::string stem = frame_stem(scene_name_, frame);
  const std::filesystem::path frames_dir = out_dir_ / "frames";
  const std::filesystem::path block_dir = frames_dir / stem;
  std::error_code ec;
  std::filesystem::create_directories(block_dir, ec);
  if (ec) {
    throw std::runtime_error("cannot create frame folder '" + block_dir.string() + "': " +
                             ec.message());
  }

  // Order matters for crash safety: .vtu files, then the .vtm naming them, then the .pvd.
  std::vector<std::string> block_files(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::string file = std::to_string(b) + "_" + sanitize_file_name(bodies[b].name) + ".vtu";
    write_vtu(block_dir / file, time, bodies[b]);
    block_files[b] = stem + "/" + file;  // relative to the .vtm's folder, as VTK expects
  }

  const std::filesystem::path vtm = frames_dir / (stem + ".vtm");
  write_file_atomically(vtm, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n"
           "  <vtkMultiBlockDataSet>\n";
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      out << "    <DataSet index=\"" << b << "\" name=\"" << xml_escape(bodies[b].name)
          << "\" file=\"" << xml_escape(block_files[b]) << "\"/>\n";
    }
    out << "  </vtkMultiBlockDataSet>\n</VTKFile>\n";
  });

  frames_.emplace_back(time, "frames/" + stem + ".vtm");
  try {
    write_pvd();
  } catch (...) {
    // The frame is not listed, so it does not count; a later write() reuses its number.
    frames_.pop_back();
    throw;
  }
}

int FrameWriter::frame_count() const { return static_cast<int>(frames_.size()); }

void FrameWriter::continue_from(std::vector<std::pair<double, std::string>> frames) {
  frames_ = std::move(frames);
  write_pvd();
}

std::filesystem::path FrameWriter::pvd_path() const { return out_dir_ / (scene_name_ + ".pvd"); }

void FrameWriter::write_pvd() const { write_pvd_collection(pvd_path(), frames_); }

void write_pvd_collection(const std::filesystem::path& pvd, const std::vector<std::pair<double, std::string>>& frames) {
  write_file_atomically(pvd, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
           "  <Collection>\n";
    for (const auto& [time, file] : frames) {
      out << "    <DataSet timestep=\"" << format_double(time) << "\" part=\"0\" file=\""
          << xml_escape(file) << "\"/>\n";
    }
    out << "  </Collection>\n</VTKFile>\n";
  });
}

}  // namespace stiffsoft
