#pragma once
/// @file A content-addressed cache of tet meshes: the same recipe is meshed by gmsh only once.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <stiffsoft/meshing/tet_meshing.hpp>

namespace stiffsoft {

/// FNV-1a, 64 bit: h ← (h ⊕ byte) · 1099511628211, starting from `h` (default: the offset basis
/// 14695981039346656037). Not cryptographic; enough to tell recipes apart.
std::uint64_t fnv1a_64(std::string_view bytes, std::uint64_t h = 14695981039346656037ull);

/// The canonical text of a recipe: format version, gmsh API version, and what the mesh depends on,
/// numbers as exact hexadecimal floats. Primitive: type, the sizes its shape uses, h,
/// elements_per_circle. File: lowercase extension, its size in bytes, and (except for .msh) h,
/// elements_per_circle, keep_surface, feature_angle_deg. Not the file's path or name, nor `verbose`.
std::string tet_mesh_recipe_text(const TetMeshRecipe& recipe);

/// fnv1a_64 of tet_mesh_recipe_text() followed by the file's bytes (for a file recipe).
/// A .geo file's own includes (Merge, Include) are not part of the hash.
/// @throws std::runtime_error naming the file when it cannot be read
std::uint64_t tet_mesh_recipe_hash(const TetMeshRecipe& recipe);

/// The cache folder: `folder` when not empty; else $STIFFSOFT_MESH_CACHE when set and not empty;
/// else $XDG_CACHE_HOME/stiffsoft/meshes; else $HOME/.cache/stiffsoft/meshes; else
/// <temporary directory>/stiffsoft/meshes. Does not create it.
std::filesystem::path tet_mesh_cache_folder(const std::filesystem::path& folder = {});

/// A tet mesh and where it came from.
struct CachedTetMesh {
  /// the mesh
  TetMesh mesh;
  /// true when it was read from the cache (gmsh did not run)
  bool from_cache = false;
  /// the cache entry: <folder>/<16 hex digits of the hash>.tetmesh
  std::filesystem::path cache_file;
  /// empty when the cache worked; otherwise why an entry was ignored (unreadable, corrupt) or
  /// could not be written; the mesh is still valid
  std::string cache_problem;
};

/// The mesh of `recipe`, from the cache when an entry for tet_mesh_recipe_hash(recipe) exists
/// (no gmsh call; the entry is checked with check_tet_mesh and must carry the same hash), otherwise
/// made by make_tet_mesh(recipe) and stored with write_tet_mesh_binary (atomically: temporary file
/// + rename, so concurrent runs never see a partial entry). A corrupt entry is replaced.
/// @param folder see tet_mesh_cache_folder(); created when missing
/// @throws what make_tet_mesh throws; never for a cache problem (see cache_problem)
CachedTetMesh cached_tet_mesh(const TetMeshRecipe& recipe, const std::filesystem::path& folder = {});

}  // namespace stiffsoft
