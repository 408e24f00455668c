#include <stiffsoft/scene/element_limits.hpp>

#include <cmath>

#include <stiffsoft/meshing/primitive.hpp>
#include <stiffsoft/meshing/tet_meshing.hpp>
#include <stiffsoft/scene/scene_fields.hpp>
#include <stiffsoft/libfem/format_number.hpp>
#include <stiffsoft/scene/scene_schema.hpp>

namespace stiffsoft {

void check_primitive_triangles(const BodyDescription& body, const ElementLimits& limits, const std::string& file,
                               const std::string& path) {
  if (!body.mesh.primitive) return;
  const PrimitiveShape& shape = *body.mesh.primitive;
  const double count = primitive_triangle_count(shape);
  if (!(count > double(limits.max_triangles))) return;
  const std::string flag = "raise the limit with `stiffsoft run --max-triangles N`";
  if (shape.type == PrimitiveShape::Type::Box || shape.type == PrimitiveShape::Type::Plane)
    throw SceneError(file, path + ".mesh",
                     "body \"" + body.name + "\" (" + scene_fields::enum_name(shape.type) + ") has " +
                         fem::format_significant(count) + " triangles, more than the limit of " +
                         std::to_string(limits.max_triangles) + "; " + flag);
  // The largest resolution under the limit, by bisection on the exact count.
  PrimitiveShape fits = shape;
  int low = 3, high = shape.resolution;
  while (high - low > 1) {
    fits.resolution = low + (high - low) / 2;
    (primitive_triangle_count(fits) <= double(limits.max_triangles) ? low : high) = fits.resolution;
  }
  throw SceneError(file, path + ".mesh.resolution",
                   "body \"" + body.name + "\" (" + scene_fields::enum_name(shape.type) + ", resolution " +
                       std::to_string(shape.resolution) + ") would have " + fem::format_significant(count) +
                       " triangles, more than the limit of " + std::to_string(limits.max_triangles) +
                       "; use a resolution of at most " + std::to_string(low) + ", or " + flag);
}

void check_tet_count(const BodyDescription& body, double volume, double h, const ElementLimits& limits,
                     const std::string& file, const std::string& path) {
  if (expected_tet_count(volume, h) > double(limits.max_tets))
    throw tet_count_error(body, volume, h, limits, file, path);
}

SceneError tet_count_error(const BodyDescription& body, double volume, double h, const ElementLimits& limits,
                           const std::string& file, const std::string& path) {
  const double expected = expected_tet_count(volume, h);
  // The h at which the estimate equals the limit (the count goes as 1/h³), rounded up to 3
  // digits so it fits.
  const double h_min = std::cbrt(expected_tet_count(volume, 1.0) / double(limits.max_tets));
  const double unit = std::pow(10.0, std::floor(std::log10(h_min)) - 2);
  const double h_fits = std::ceil(h_min / unit * (1 - 1e-12)) * unit;
  return SceneError(file, path + ".mesh_size",
                    "body \"" + body.name + "\" would need about " + fem::format_significant(expected) +
                       " tetrahedra (volume " + fem::format_significant(volume) + " m³ at mesh_size " + fem::format_significant(h) +
                       " m: V / (h³/(6√2))), more than the limit of " + std::to_string(limits.max_tets) +
                       "; use a mesh_size of at least " + fem::format_significant(h_fits) +
                       " m, or raise the limit with `stiffsoft run --max-tets N`");
}

}  // namespace stiffsoft
