#include <stiffsoft/meshing/read_surface_mesh.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace stiffsoft {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message) {
  throw std::runtime_error(path.string() + ": " + message);
}

[[noreturn]] void fail_at(const std::filesystem::path& path, size_t line, const std::string& message) {
  throw std::runtime_error(path.string() + ":" + std::to_string(line) + ": " + message);
}

SurfaceMesh to_mesh(const std::vector<std::array<double, 3>>& V, const std::vector<std::array<int, 3>>& F) {
  SurfaceMesh m;
  m.V.resize(static_cast<Eigen::Index>(V.size()), 3);
  m.F.resize(static_cast<Eigen::Index>(F.size()), 3);
  for (size_t i = 0; i < V.size(); ++i)
    for (int d = 0; d < 3; ++d) m.V(static_cast<Eigen::Index>(i), d) = V[i][d];
  for (size_t i = 0; i < F.size(); ++i)
    for (int d = 0; d < 3; ++d) m.F(static_cast<Eigen::Index>(i), d) = F[i][d];
  return m;
}

bool parse_double(const std::string& token, double& value) {
  try {
    size_t used = 0;
    value = std::stod(token, &used);
    return used == token.size() && std::isfinite(value);
  } catch (const std::exception&) {
    return false;
  }
}

SurfaceMesh read_obj(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open file");
  std::vector<std::array<double, 3>> V;
  std::vector<std::array<int, 3>> F;
  std::vector<size_t> face_line;  // source line of each triangle, for index errors found at the end
  std::string line, tag, token;
  std::vector<int> polygon;
  for (size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line);
    if (!(words >> tag) || tag[0] == '#') continue;
    if (tag == "v") {
      std::array<double, 3> p{};
      for (int d = 0; d < 3; ++d)
        if (!(words >> token) || !parse_double(token, p[d]))
          fail_at(path, number, "expected `v x y z` with three finite numbers");
      V.push_back(p);
    } else if (tag == "f") {
      polygon.clear();
      while (words >> token) {
        const std::string index_text = token.substr(0, token.find('/'));
        int index = 0;
        try {
          size_t used = 0;
          index = std::stoi(index_text, &used);
          if (used != index_text.size()) throw std::invalid_argument("trailing characters");
        } catch (const std::exception&) {
          fail_at(path, number, "expected a vertex index in `" + token + "`");
        }
        if (index == 0) fail_at(path, number, "vertex index 0 (OBJ indices start at 1)");
        // A negative index is relative to the vertices read so far (-1 is the last one).
        const long resolved = index > 0 ? index - 1L : static_cast<long>(V.size()) + index;
        if (resolved < 0) fail_at(path, number, "relative vertex index " + std::to_string(index) + " before the first vertex");
        polygon.push_back(static_cast<int>(resolved));
      }
      if (polygon.size() < 3)
        fail_at(path, number, "expected a face with at least 3 vertices, got " + std::to_string(polygon.size()));
      for (size_t k = 1; k + 1 < polygon.size(); ++k) {
        F.push_back({polygon[0], polygon[k], polygon[k + 1]});
        face_line.push_back(number);
      }
    }
  }
  for (size_t f = 0; f < F.size(); ++f)
    for (int index : F[f])
      if (index >= static_cast<int>(V.size()))
        fail_at(path, face_line[f],
                "vertex index " + std::to_string(index + 1) + " out of range (" + std::to_string(V.size()) + " vertices)");
  if (F.empty()) fail(path, "no faces (`f` lines) found");
  return to_mesh(V, F);
}

// Merges bit-identical points (std::map compares by value; -0 and +0 merge, NaN is rejected earlier).
struct VertexMerger {
  std::map<std::array<double, 3>, int> index_of;
  std::vector<std::array<double, 3>> V;
  int operator()(const std::array<double, 3>& p) {
    const auto [it, inserted] = index_of.try_emplace(p, static_cast<int>(V.size()));
    if (inserted) V.push_back(p);
    return it->second;
  }
};

SurfaceMesh read_binary_stl(const std::filesystem::path& path, const std::string& bytes) {
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  VertexMerger merge;
  std::vector<std::array<int, 3>> F;
  F.reserve(count);
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + 84 + 50 * static_cast<size_t>(t);
    std::array<int, 3> face{};
    for (int k = 0; k < 3; ++k) {
      float xyz[3];
      std::memcpy(xyz, record + 12 + 12 * k, 12);  // skip the 12-byte normal
      const std::array<double, 3> p{xyz[0], xyz[1], xyz[2]};
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        fail(path, "triangle " + std::to_string(t) + " has a non-finite coordinate");
      face[k] = merge(p);
    }
    F.push_back(face);
  }
  if (F.empty()) fail(path, "binary STL with no triangles");
  return to_mesh(merge.V, F);
}

SurfaceMesh read_ascii_stl(const std::filesystem::path& path, const std::string& text) {
  std::istringstream in(text);
  VertexMerger merge;
  std::vector<std::array<int, 3>> F;
  std::vector<int> loop;
  bool in_loop = false;
  std::string line, word, token;
  for (size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line);
    if (!(words >> word)) continue;
    std::transform(word.begin(), word.end(), word.begin(), [](unsigned char c) { return std::tolower(c); });
    if (word == "outer") {
      if (in_loop) fail_at(path, number, "`outer loop` inside another loop");
      in_loop = true;
      loop.clear();
    } else if (word == "vertex") {
      if (!in_loop) fail_at(path, number, "`vertex` outside `outer loop` … `endloop`");
      std::array<double, 3> p{};
      for (int d = 0; d < 3; ++d)
        if (!(words >> token) || !parse_double(token, p[d]))
          fail_at(path, number, "expected `vertex x y z` with three finite numbers");
      loop.push_back(merge(p));
    } else if (word == "endloop") {
      if (!in_loop) fail_at(path, number, "`endloop` without `outer loop`");
      if (loop.size() != 3)
        fail_at(path, number, "expected 3 vertices in a facet loop, got " + std::to_string(loop.size()));
      F.push_back({loop[0], loop[1], loop[2]});
      in_loop = false;
    } else if (word != "solid" && word != "facet" && word != "endfacet" && word != "endsolid") {
      fail_at(path, number, "unexpected `" + word + "` (expected solid, facet, outer loop, vertex, endloop, endfacet or endsolid)");
    }
  }
  if (in_loop) fail(path, "file ends inside a facet loop");
  if (F.empty()) fail(path, "ASCII STL with no facets");
  return to_mesh(merge.V, F);
}

SurfaceMesh read_stl(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open file");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Binary files may also start with "solid", so the size test decides first.
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() == 84 + 50 * static_cast<size_t>(count)) return read_binary_stl(path, bytes);
  }
  size_t start = 0;
  while (start < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[start]))) ++start;
  if (bytes.compare(start, 5, "solid") != 0)
    fail(path, "neither a binary STL (size " + std::to_string(bytes.size()) +
                   " bytes is not 84 + 50 × the triangle count in the header) nor an ASCII STL (starting with `solid`)");
  return read_ascii_stl(path, bytes);
}

}  // namespace

SurfaceMesh read_surface_mesh(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension == ".obj") return read_obj(path);
  if (extension == ".stl") return read_stl(path);
  fail(path, "unsupported surface mesh format `" + extension + "` (expected .obj or .stl)");
}

}  // namespace stiffsoft
