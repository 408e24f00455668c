#pragma once
/// @file Reading triangle surfaces from .obj and .stl files.

#include <filesystem>

#include <stiffsoft/meshing/surface_mesh.hpp>

namespace stiffsoft {

/// Reads a triangle surface from a file, chosen by extension (case-insensitive):
/// - `.obj`: `v x y z` and `f i j k ...` lines; indices are 1-based, negative ones count back from
///   the last vertex read so far, `i/t/n`, `i//n` and `i/t` forms are accepted (only `i` is used),
///   polygons are fan-triangulated (0, k, k+1); every other line (`vn`, `vt`, `o`, `g`, `s`,
///   `usemtl`, `#`, …) is ignored.
/// - `.stl`: binary (detected by its size, 84 + 50·n bytes) or ASCII (`solid … facet … vertex …`);
///   vertices with bit-identical coordinates are merged, in order of first appearance.
/// No orientation repair and no checks beyond the syntax: call check_closed_manifold() next.
/// @throws std::runtime_error naming the file (and line for text formats) and what was expected.
SurfaceMesh read_surface_mesh(const std::filesystem::path& path);

}  // namespace stiffsoft
