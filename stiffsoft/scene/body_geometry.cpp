#include <stiffsoft/scene/body_geometry.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>

#include <stiffsoft/scene/scene_schema.hpp>
#include <stiffsoft/meshing/mesh_checks.hpp>
#include <stiffsoft/meshing/primitive.hpp>
#include <stiffsoft/meshing/read_surface_mesh.hpp>
#include <stiffsoft/meshing/tet_boundary.hpp>
#include <stiffsoft/meshing/tet_mesh_cache.hpp>
#include <stiffsoft/meshing/tet_quality.hpp>

namespace stiffsoft {

namespace {

std::string lower_extension(const std::filesystem::path& file) {
  std::string e = file.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

void check_surface(const SurfaceMesh& mesh, const BodyDescription& body, const std::string& file,
                   const std::string& path) {
  if (const auto problem = closed_manifold_problem(mesh))
    throw SceneError(file, path + ".mesh",
                     "body '" + body.name + "' needs a closed, manifold, outward-oriented surface: " + *problem);
  if (const auto faces = find_self_intersection(mesh))
    throw SceneError(file, path + ".mesh",
                     "body '" + body.name + "' has a self-intersecting surface (faces " + std::to_string(faces->first) +
                         " and " + std::to_string(faces->second) + ")");
}

}  // namespace

bool is_volume_file(const std::filesystem::path& file) {
  const std::string e = lower_extension(file);
  return e == ".msh" || e == ".step" || e == ".stp" || e == ".brep" || e == ".geo";
}

SurfaceMesh body_surface(const BodyDescription& body, const ElementLimits& limits, const std::string& file,
                         const std::string& path) {
  SurfaceMesh mesh;
  if (!body.mesh.primitive && is_volume_file(body.mesh.file)) {
    const SurfaceMesh none;
    const TetMesh tets = body_tet_mesh(body, soft_mesh_size(body, none, file, path), limits, file, path);
    mesh = boundary_surface(tets, body.name).surface;
  } else {
    check_primitive_triangles(body, limits, file, path);
    try {
      mesh = body.mesh.primitive ? make_primitive(*body.mesh.primitive) : read_surface_mesh(body.mesh.file);
    } catch (const std::exception& e) {
      throw SceneError(file, path + ".mesh", e.what());
    }
    mesh.V = mesh.V * body.scale.asDiagonal();
  }
  check_surface(mesh, body, file, path);
  return mesh;
}

double soft_mesh_size(const BodyDescription& body, const SurfaceMesh& surface, const std::string& file,
                      const std::string& path) {
  if (body.mesh_size) return *body.mesh_size;
  if (!body.mesh.primitive && is_volume_file(body.mesh.file)) {
    if (lower_extension(body.mesh.file) == ".msh") return 1.0;  // unused: a .msh is read as is
    throw SceneError(file, path + ".mesh_size",
                     "required for body '" + body.name + "': CAD and .geo files need a target tet size (m)");
  }
  return (surface.V.colwise().maxCoeff() - surface.V.colwise().minCoeff()).norm() / 8.0;
}

TetMesh body_tet_mesh(const BodyDescription& body, double h, const ElementLimits& limits, const std::string& file,
                      const std::string& path) {
  TetMeshRecipe recipe;
  recipe.primitive = body.mesh.primitive;
  recipe.file = body.mesh.file;
  recipe.options.h = h;
  recipe.options.max_tets = double(limits.max_tets);
  CachedTetMesh cached;
  try {
    cached = cached_tet_mesh(recipe);
  } catch (const TetCountLimitError& e) {
    throw tet_count_error(body, e.volume(), h, limits, file, path);
  } catch (const std::exception& e) {
    throw SceneError(file, path + ".mesh", "cannot tet-mesh body '" + body.name + "': " + e.what());
  }
  if (!cached.cache_problem.empty()) spdlog::warn("mesh cache: {}", cached.cache_problem);
  TetMesh mesh = std::move(cached.mesh);
  mesh.X = mesh.X * body.scale.asDiagonal();
  try {
    check_tet_mesh(mesh, "body '" + body.name + "'");
  } catch (const std::exception& e) {
    throw SceneError(file, path + ".mesh", e.what());
  }
  spdlog::info("body '{}': tet mesh{} ({}), h = {:.3g} m: {}", body.name, cached.from_cache ? " from cache" : "",
               cached.cache_file.filename().string(), h, summary(tet_quality(mesh)));
  return mesh;
}

}  // namespace stiffsoft
