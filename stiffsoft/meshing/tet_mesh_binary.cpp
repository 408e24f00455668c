#include <stiffsoft/meshing/tet_mesh_binary.hpp>

#include <unistd.h>

#include <atomic>
#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace stiffsoft {
namespace {

static_assert(std::endian::native == std::endian::little, "the tet mesh binary format is little-endian");

constexpr char magic[8] = {'S', 'T', 'S', 'F', 'T', 'E', 'T', 'M'};
constexpr std::uint32_t version = 1;

template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// Reads fixed-size values from a byte buffer, failing on a short buffer.
struct Reader {
  const std::string& bytes;
  std::size_t at = 0;
  const std::string& what;

  template <class T>
  T get() {
    T value;
    if (bytes.size() - at < sizeof(T)) throw std::runtime_error(what + ": truncated tet mesh file");
    std::memcpy(&value, bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return value;
  }
  void require(std::uint64_t count, std::size_t size) {
    if (count > (bytes.size() - at) / size) throw std::runtime_error(what + ": truncated tet mesh file");
  }
};

}  // namespace

void write_tet_mesh_binary(const std::filesystem::path& file, const TetMesh& mesh, std::uint64_t tag) {
  std::string out(magic, sizeof magic);
  put(out, version);
  put(out, tag);
  put(out, static_cast<std::int64_t>(mesh.X.rows()));
  put(out, static_cast<std::int64_t>(mesh.T.rows()));
  for (Eigen::Index i = 0; i < mesh.X.rows(); ++i)
    for (int d = 0; d < 3; ++d) put(out, mesh.X(i, d));
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t)
    for (int k = 0; k < 4; ++k) put(out, static_cast<std::int32_t>(mesh.T(t, k)));
  put(out, static_cast<std::uint64_t>(mesh.node_sets.size()));
  for (const auto& [name, nodes] : mesh.node_sets) {
    put(out, static_cast<std::uint64_t>(name.size()));
    out += name;
    put(out, static_cast<std::uint64_t>(nodes.size()));
    for (int i : nodes) put(out, static_cast<std::int32_t>(i));
  }

  static std::atomic<unsigned long> counter{0};
  std::string name = ".";
  name += file.filename().string();
  name += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1));
  const std::filesystem::path tmp = file.parent_path() / name;
  std::error_code ignored;
  {
    std::ofstream stream(tmp, std::ios::binary | std::ios::trunc);
    if (!stream)
      throw std::runtime_error(file.string() + ": cannot create temporary file '" + tmp.string() + "'");
    stream.write(out.data(), static_cast<std::streamsize>(out.size()));
    stream.close();
    if (!stream) {
      std::filesystem::remove(tmp, ignored);
      throw std::runtime_error(file.string() + ": write failed (disk full or I/O error)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error(file.string() + ": rename from '" + tmp.string() + "' failed: " + ec.message());
  }
}

TetMesh read_tet_mesh_binary(const std::filesystem::path& file, std::uint64_t* tag) {
  const std::string what = file.string();
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw std::runtime_error(what + ": cannot open file");
  const std::string bytes{std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
  if (bytes.size() < sizeof magic || std::memcmp(bytes.data(), magic, sizeof magic) != 0)
    throw std::runtime_error(what + ": not a stiffsoft tet mesh file (bad magic)");
  Reader r{bytes, sizeof magic, what};
  if (const auto v = r.get<std::uint32_t>(); v != version)
    throw std::runtime_error(what + ": tet mesh file version " + std::to_string(v) + ", expected " +
                             std::to_string(version));
  const auto stored_tag = r.get<std::uint64_t>();
  const auto num_nodes = r.get<std::int64_t>();
  const auto num_tets = r.get<std::int64_t>();
  if (num_nodes < 0 || num_tets < 0) throw std::runtime_error(what + ": negative sizes in tet mesh file");
  r.require(static_cast<std::uint64_t>(num_nodes), 3 * sizeof(double));
  TetMesh mesh;
  mesh.X.resize(num_nodes, 3);
  for (Eigen::Index i = 0; i < num_nodes; ++i)
    for (int d = 0; d < 3; ++d) mesh.X(i, d) = r.get<double>();
  r.require(static_cast<std::uint64_t>(num_tets), 4 * sizeof(std::int32_t));
  mesh.T.resize(num_tets, 4);
  for (Eigen::Index t = 0; t < num_tets; ++t)
    for (int k = 0; k < 4; ++k) mesh.T(t, k) = r.get<std::int32_t>();
  const auto num_sets = r.get<std::uint64_t>();
  for (std::uint64_t s = 0; s < num_sets; ++s) {
    const auto length = r.get<std::uint64_t>();
    r.require(length, 1);
    std::string name = bytes.substr(r.at, length);
    r.at += length;
    const auto count = r.get<std::uint64_t>();
    r.require(count, sizeof(std::int32_t));
    std::vector<int> nodes(count);
    for (auto& i : nodes) i = r.get<std::int32_t>();
    mesh.node_sets[std::move(name)] = std::move(nodes);
  }
  if (r.at != bytes.size()) throw std::runtime_error(what + ": trailing bytes after the tet mesh");
  check_tet_mesh(mesh, what);
  if (tag) *tag = stored_tag;
  return mesh;
}

}  // namespace stiffsoft
