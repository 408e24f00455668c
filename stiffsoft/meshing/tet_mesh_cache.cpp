#include <stiffsoft/meshing/tet_mesh_cache.hpp>

#include <gmsh.h>  // GMSH_API_VERSION only: a cache hit must not call gmsh

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

#include <stiffsoft/meshing/tet_mesh_binary.hpp>

namespace stiffsoft {
namespace {

/// exact text of a double (hexadecimal significand and binary exponent)
std::string exact(double x) {
  char text[64];
  std::snprintf(text, sizeof text, "%a", x);
  return text;
}

std::string lowercase_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot open file");
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw std::runtime_error(file.string() + ": read error");
  return bytes;
}

std::string hex(std::uint64_t h) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

const char* env(const char* name) {
  const char* value = std::getenv(name);
  return value && *value ? value : nullptr;
}

}  // namespace

std::uint64_t fnv1a_64(std::string_view bytes, std::uint64_t h) {
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

std::string tet_mesh_recipe_text(const TetMeshRecipe& recipe) {
  const TetMeshOptions& o = recipe.options;
  std::string text = "stiffsoft tet mesh recipe 1\ngmsh " GMSH_API_VERSION "\n";
  const std::string sizes =
      "h " + exact(o.h) + "\nelements_per_circle " + std::to_string(o.elements_per_circle) + "\n";
  if (recipe.primitive) {
    const PrimitiveShape& s = *recipe.primitive;
    using Type = PrimitiveShape::Type;
    switch (s.type) {
      case Type::Box:
      case Type::Plane:
        // A plane is meshed as a box of its extents: the same mesh.
        text +=
            "box " + exact(s.extents.x()) + " " + exact(s.extents.y()) + " " + exact(s.extents.z()) + "\n";
        break;
      case Type::Sphere:
        text += "sphere " + exact(s.radius) + "\n";
        break;
      case Type::Cylinder:
        text += "cylinder " + exact(s.radius) + " " + exact(s.height) + "\n";
        break;
      case Type::Torus:
        text += "torus " + exact(s.radius) + " " + exact(s.minor_radius) + "\n";
        break;
    }
    return text + sizes;
  }
  const std::string ext = lowercase_extension(recipe.file);
  std::error_code ec;
  const auto size = std::filesystem::file_size(recipe.file, ec);
  text += "file " + ext + " " + std::to_string(ec ? 0 : size) + " bytes\n";
  if (ext != ".msh")
    text += sizes + "keep_surface " + std::to_string(o.keep_surface ? 1 : 0) + "\nfeature_angle_deg " +
            exact(o.feature_angle_deg) + "\n";
  return text;
}

std::uint64_t tet_mesh_recipe_hash(const TetMeshRecipe& recipe) {
  std::uint64_t h = fnv1a_64(tet_mesh_recipe_text(recipe));
  if (!recipe.primitive) h = fnv1a_64(read_bytes(recipe.file), h);
  return h;
}

std::filesystem::path tet_mesh_cache_folder(const std::filesystem::path& folder) {
  if (!folder.empty()) return folder;
  if (const char* cache = env("STIFFSOFT_MESH_CACHE")) return cache;
  if (const char* xdg = env("XDG_CACHE_HOME")) return std::filesystem::path(xdg) / "stiffsoft" / "meshes";
  if (const char* home = env("HOME")) return std::filesystem::path(home) / ".cache" / "stiffsoft" / "meshes";
  return std::filesystem::temp_directory_path() / "stiffsoft" / "meshes";
}

CachedTetMesh cached_tet_mesh(const TetMeshRecipe& recipe, const std::filesystem::path& folder) {
  const std::uint64_t hash = tet_mesh_recipe_hash(recipe);
  CachedTetMesh result;
  const std::filesystem::path dir = tet_mesh_cache_folder(folder);
  result.cache_file = dir / (hex(hash) + ".tetmesh");

  std::error_code ec;
  if (std::filesystem::exists(result.cache_file, ec)) {
    try {
      std::uint64_t stored = 0;
      TetMesh mesh = read_tet_mesh_binary(result.cache_file, &stored);
      if (stored != hash)
        throw std::runtime_error(result.cache_file.string() + ": holds the mesh of another recipe (hash " +
                                 hex(stored) + ")");
      result.mesh = std::move(mesh);
      result.from_cache = true;
      return result;
    } catch (const std::runtime_error& e) {
      result.cache_problem = std::string("ignored cache entry: ") + e.what();
    }
  }

  result.mesh = make_tet_mesh(recipe);
  try {
    std::filesystem::create_directories(dir, ec);
    if (ec) throw std::runtime_error(dir.string() + ": cannot create cache folder: " + ec.message());
    write_tet_mesh_binary(result.cache_file, result.mesh, hash);
  } catch (const std::runtime_error& e) {
    result.cache_problem +=
        (result.cache_problem.empty() ? "" : "; ") + std::string("not cached: ") + e.what();
  }
  return result;
}

}  // namespace stiffsoft
