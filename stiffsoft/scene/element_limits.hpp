#pragma once
/// @file Limits before work (docs/robustness.md): how many tetrahedra and triangles one body may
/// ask for, estimated from the scene before any meshing, so that a slip in mesh_size or
/// resolution (1e-6 m, 2e9) is refused at once instead of hanging in gmsh or exhausting memory.

#include <cstdint>
#include <string>

#include <stiffsoft/scene/scene.hpp>
#include <stiffsoft/scene/scene_schema.hpp>

namespace stiffsoft {

/// The largest body a scene may build; `stiffsoft run --max-tets N --max-triangles N` raise them.
struct ElementLimits {
  std::int64_t max_tets = 2'000'000;       ///< expected tetrahedra of one soft body (expected_tet_count())
  std::int64_t max_triangles = 1'000'000;  ///< triangles of one primitive's surface (primitive_triangle_count())
};

/// Throws SceneError (`<path>.mesh.resolution`, naming the body, the count, the limit, the
/// largest resolution that fits and the `--max-triangles` flag; `<path>.mesh` for a box or
/// plane, which always have 12) when the body's primitive would have more than
/// limits.max_triangles triangles. Nothing for a mesh file.
void check_primitive_triangles(const BodyDescription& body, const ElementLimits& limits, const std::string& file,
                               const std::string& path);

/// The error for a body whose volume (m³) meshed at edge length h (m) is expected to give more
/// than limits.max_tets tetrahedra (expected_tet_count(), tet_meshing.hpp; no further safety
/// factor): SceneError at `<path>.mesh_size`, naming the body, the estimate, the limit, the
/// smallest mesh_size that fits and the `--max-tets` flag.
SceneError tet_count_error(const BodyDescription& body, double volume, double h, const ElementLimits& limits,
                           const std::string& file, const std::string& path);

/// Throws tet_count_error() when expected_tet_count(volume, h) is above limits.max_tets.
void check_tet_count(const BodyDescription& body, double volume, double h, const ElementLimits& limits,
                     const std::string& file, const std::string& path);

}  // namespace stiffsoft
