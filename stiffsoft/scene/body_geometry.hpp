#pragma once
/// @file A body's geometry in its own frame (scaled, not yet rotated or placed): the closed
/// surface every body has, and the tetrahedral mesh a soft body needs.

#include <filesystem>
#include <optional>
#include <string>

#include <stiffsoft/scene/element_limits.hpp>
#include <stiffsoft/scene/scene.hpp>
#include <stiffsoft/meshing/surface_mesh.hpp>
#include <stiffsoft/meshing/tet_mesh.hpp>

namespace stiffsoft {

/// True for mesh files that hold a volume (tet-meshed by gmsh or read as tets): .msh, .step,
/// .stp, .brep, .geo; false for surface files (.obj, .stl).
bool is_volume_file(const std::filesystem::path& file);

/// The body's closed surface, scaled by `scale`, checked closed, manifold, outward-oriented and
/// free of self-intersections. Volume files are tet-meshed (cached) and their boundary taken.
/// A primitive with more triangles than `limits` allow is refused before it is made.
/// Errors are SceneError naming `file` and `path` (the body's JSON path).
SurfaceMesh body_surface(const BodyDescription& body, const ElementLimits& limits, const std::string& file,
                         const std::string& path);

/// The target tet edge length of a soft body: mesh_size, or 1/8 of the diagonal of the box
/// around `surface`. CAD and .geo files need an explicit mesh_size (SceneError otherwise).
double soft_mesh_size(const BodyDescription& body, const SurfaceMesh& surface, const std::string& file,
                      const std::string& path);

/// The body's tet mesh (gmsh, cached by content), scaled by `scale`, checked (no degenerate or
/// inverted tet); its quality is logged. `h` is the target edge length (m). A CAD or .geo file
/// expected to give more tets than `limits` allow is refused once loaded, before gmsh meshes it
/// (TetMeshOptions::max_tets; tet_count_error()).
TetMesh body_tet_mesh(const BodyDescription& body, double h, const ElementLimits& limits, const std::string& file,
                      const std::string& path);

}  // namespace stiffsoft
