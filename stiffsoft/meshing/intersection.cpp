#include <stiffsoft/meshing/intersection.hpp>

namespace stiffsoft {

std::optional<SurfaceOverlap> find_overlap(const std::vector<SurfaceMesh>& surfaces) {
  if (auto hit = find_intersection(surfaces)) return SurfaceOverlap{*hit};
  if (auto inside = find_containment(surfaces)) return SurfaceOverlap{*inside};
  return std::nullopt;
}

std::string describe(const SurfaceOverlap& overlap, const std::vector<std::string>& names) {
  const auto name = [&](int s) {
    return s < static_cast<int>(names.size()) ? "'" + names[s] + "'" : "surface " + std::to_string(s);
  };
  if (const auto* hit = std::get_if<TriangleIntersection>(&overlap))
    return name(hit->surface_a) + " and " + name(hit->surface_b) + " intersect: face " + std::to_string(hit->face_a) +
           " of " + name(hit->surface_a) + " meets face " + std::to_string(hit->face_b) + " of " + name(hit->surface_b);
  const auto& inside = std::get<SurfaceContainment>(overlap);
  return name(inside.inner) + " lies inside " + name(inside.outer) + " (its vertex " + std::to_string(inside.vertex) +
         " is enclosed, no faces cross)";
}

}  // namespace stiffsoft
