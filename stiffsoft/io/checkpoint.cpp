#include <stiffsoft/io/checkpoint.hpp>

#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include <stiffsoft/io/atomic_file.hpp>
#include <stiffsoft/meshing/tet_mesh_cache.hpp>
#include <stiffsoft/scene/scene_loader.hpp>

namespace stiffsoft {

namespace {

/// Format and version, the file's first bytes. Version 2 added the linear solver's memory
/// (SimulationState::solver), version 3 the sleeping bodies (SimulationState::sleeping).
constexpr char kTag[] = "stiffsoft checkpoint 3\n";

/// Appends raw bytes of values (native byte order: a checkpoint is read back on the same machine).
class Writer {
 public:
  template <class T>
  void put(const T& value) {
    bytes.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void put(const std::string& s) {
    put(std::uint64_t(s.size()));
    bytes += s;
  }
  void put(const Eigen::VectorXd& v) {
    put(std::uint64_t(v.size()));
    if (v.size() > 0)  // an empty vector's data() is null
      bytes.append(reinterpret_cast<const char*>(v.data()), sizeof(double) * std::size_t(v.size()));
  }
  void put(const FrameList& frames) {
    put(std::uint64_t(frames.size()));
    for (const auto& [time, file] : frames) {
      put(time);
      put(file);
    }
  }
  std::string bytes;
};

/// Reads what Writer wrote; a ResumeError when the bytes run out.
class Reader {
 public:
  Reader(std::string_view bytes, const std::filesystem::path& file) : m_bytes(bytes), m_file(file) {}
  template <class T>
  T get() {
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    return std::string(take(n), n);
  }
  Eigen::VectorXd get_vector() {
    const auto n = get<std::uint64_t>();
    if (n > m_bytes.size() / sizeof(double)) throw_truncated();
    const char* data = take(n * sizeof(double));
    Eigen::VectorXd v{Eigen::Index(n)};
    if (n > 0) std::memcpy(v.data(), data, n * sizeof(double));  // an empty vector's data() is null
    return v;
  }
  FrameList get_frame_list() {
    const auto n = get<std::uint64_t>();
    if (n > m_bytes.size()) throw_truncated();
    FrameList frames;
    for (std::uint64_t i = 0; i < n; ++i) {
      const double time = get<double>();
      frames.emplace_back(time, get_string());
    }
    return frames;
  }
  bool at_end() const { return m_bytes.empty(); }

 private:
  const char* take(std::uint64_t n) {
    if (n > m_bytes.size()) throw_truncated();
    const char* p = m_bytes.data();
    m_bytes.remove_prefix(n);
    return p;
  }
  [[noreturn]] void throw_truncated() const {
    throw ResumeError(m_file.string() + ": damaged checkpoint (truncated)");
  }
  std::string_view m_bytes;
  std::filesystem::path m_file;
};

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ResumeError(file.string() + ": cannot be read");
  return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace

std::uint64_t scene_fingerprint(const SceneDescription& scene) {
  std::uint64_t h = fnv1a_64(resolved_scene_json(scene).dump());
  for (const BodyDescription& body : scene.bodies)
    if (!body.mesh.primitive) h = fnv1a_64(read_bytes(body.mesh.file), h);
  return h;
}

void write_checkpoint(const std::filesystem::path& file, const Checkpoint& c) {
  Writer w;
  w.put(c.scene_fingerprint);
  w.put(c.state.time);
  w.put(std::int64_t(c.state.step));
  for (const Eigen::VectorXd* v : {&c.state.q, &c.state.qdot, &c.state.q_prev, &c.state.qdot_prev}) w.put(*v);
  w.put(c.state.kappa);
  w.put(std::uint8_t(c.state.kappa_balanced));
  w.put(std::int64_t(c.state.solver.decided_nonzeros));
  w.put(std::uint8_t(c.state.solver.krylov));
  w.put(c.state.sleeping.rest_time);
  w.put(c.state.sleeping.asleep);
  w.put(c.next_frame);
  w.put(c.frames);
  w.put(c.joint_frames);
  const std::uint64_t checksum = fnv1a_64(w.bytes);
  write_file_atomically(file, [&](std::ostream& out) {
    out << kTag << w.bytes;
    out.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
  });
}

Checkpoint read_checkpoint(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file))
    throw ResumeError(file.string() + ": no checkpoint to resume from (the run was not started, or wrote no frame yet)");
  const std::string bytes = read_bytes(file);
  const std::size_t tag = sizeof kTag - 1;
  if (bytes.compare(0, tag, kTag) != 0)
    throw ResumeError(file.string() +
                      ": not a stiffsoft checkpoint of this version (expected it to start with \"" +
                      std::string(kTag, tag - 1) + "\")");
  if (bytes.size() < tag + sizeof(std::uint64_t)) throw ResumeError(file.string() + ": damaged checkpoint (truncated)");
  const std::string_view body(bytes.data() + tag, bytes.size() - tag - sizeof(std::uint64_t));
  std::uint64_t checksum;
  std::memcpy(&checksum, bytes.data() + bytes.size() - sizeof checksum, sizeof checksum);
  if (fnv1a_64(body) != checksum) throw ResumeError(file.string() + ": damaged checkpoint (checksum mismatch)");
  Reader r(body, file);
  Checkpoint c;
  c.scene_fingerprint = r.get<std::uint64_t>();
  c.state.time = r.get<double>();
  c.state.step = int(r.get<std::int64_t>());
  for (Eigen::VectorXd* v : {&c.state.q, &c.state.qdot, &c.state.q_prev, &c.state.qdot_prev}) *v = r.get_vector();
  c.state.kappa = r.get<double>();
  c.state.kappa_balanced = r.get<std::uint8_t>() != 0;
  c.state.solver.decided_nonzeros = long(r.get<std::int64_t>());
  c.state.solver.krylov = r.get<std::uint8_t>() != 0;
  c.state.sleeping.rest_time = r.get_vector();
  c.state.sleeping.asleep = r.get_vector();
  c.next_frame = r.get<double>();
  c.frames = r.get_frame_list();
  c.joint_frames = r.get_frame_list();
  if (!r.at_end()) throw ResumeError(file.string() + ": damaged checkpoint (bytes after the end)");
  return c;
}

}  // namespace stiffsoft
