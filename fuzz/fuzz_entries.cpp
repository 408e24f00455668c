#include "fuzz/fuzz_entries.hpp"

#include <unistd.h>

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include <stiffsoft/meshing/mass_moments.hpp>
#include <stiffsoft/meshing/mesh_checks.hpp>
#include <stiffsoft/meshing/read_surface_mesh.hpp>
#include <stiffsoft/meshing/tet_boundary.hpp>
#include <stiffsoft/meshing/tet_msh_io.hpp>
#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene_loader.hpp>

namespace stiffsoft::fuzz {
namespace {

/// The limits an input may build within: small enough that gmsh answers in about a second.
ElementLimits fuzz_limits() {
  ElementLimits limits;
  limits.max_tets = 20'000;
  limits.max_triangles = 20'000;
  return limits;
}

/// A per-process folder for the scratch files (two fuzzers may run at once), removed when the
/// process exits.
std::filesystem::path scratch_folder() {
  struct Folder {
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("stiffsoft-fuzz-" + std::to_string(::getpid()));
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() {
      std::error_code ignored;  // already gone
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return folder.path;
}

std::filesystem::path write_scratch(std::span<const std::uint8_t> bytes, const std::string& extension) {
  const std::filesystem::path path = scratch_folder() / scratch_name(extension);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return path;
}

/// Runs `stages`; a std::exception is the input's refusal.
template <class Stages>
Outcome outcome_of(Stages&& stages) {
  try {
    stages();
    return {true, {}};
  } catch (const std::exception& e) {
    return {false, e.what()};
  }
}

}  // namespace

std::string scratch_name(const std::string& extension) { return "input" + extension; }

Outcome scene_input(std::span<const std::uint8_t> bytes) {
  return outcome_of([&] {
    const std::string text(bytes.begin(), bytes.end());
    const SceneDescription scene =
        load_scene_from_string(text, STIFFSOFT_FUZZ_SCENE_FOLDER, scene_label, "fuzz");
    make_simulation(scene, scene_label, fuzz_limits());
  });
}

Outcome surface_mesh_input(std::span<const std::uint8_t> bytes, const std::string& extension) {
  return outcome_of([&] {
    const std::filesystem::path path = write_scratch(bytes, extension);
    const SurfaceMesh mesh = read_surface_mesh(path);
    check_closed_manifold(mesh, path.string());
    check_not_self_intersecting(mesh, path.string());
    mass_moments(mesh);
  });
}

Outcome msh_input(std::span<const std::uint8_t> bytes) {
  return outcome_of([&] {
    const std::filesystem::path path = write_scratch(bytes, ".msh");
    const TetMesh mesh = read_msh(path);
    const TetBoundary boundary = boundary_surface(mesh, path.string());
    check_closed_manifold(boundary.surface, path.string());
  });
}

InputKind input_kind(const std::string& name) {
  if (name == "scene") return InputKind::scene;
  if (name == "obj") return InputKind::obj;
  if (name == "stl") return InputKind::stl;
  if (name == "msh") return InputKind::msh;
  throw std::invalid_argument("unknown fuzz input kind '" + name + "' (scene, obj, stl, msh)");
}

Outcome run_input(InputKind kind, std::span<const std::uint8_t> bytes) {
  switch (kind) {
    case InputKind::scene: return scene_input(bytes);
    case InputKind::obj: return surface_mesh_input(bytes, ".obj");
    case InputKind::stl: return surface_mesh_input(bytes, ".stl");
    case InputKind::msh: return msh_input(bytes);
  }
  std::abort();
}

std::string input_label(InputKind kind) {
  switch (kind) {
    case InputKind::scene: return scene_label;
    case InputKind::obj: return scratch_name(".obj");
    case InputKind::stl: return scratch_name(".stl");
    case InputKind::msh: return scratch_name(".msh");
  }
  std::abort();
}

bool is_clear(const Outcome& outcome, const std::string& label) {
  return outcome.accepted || outcome.error.find(label) != std::string::npos;
}

}  // namespace stiffsoft::fuzz
