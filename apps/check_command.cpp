#include "check_command.hpp"

#include <spdlog/spdlog.h>

#include <stiffsoft/io/frame_reader.hpp>
#include <stiffsoft/meshing/intersection.hpp>

namespace stiffsoft {

int check_frames(const std::filesystem::path& pvd) {
  const std::vector<PvdEntry> entries = read_pvd(pvd);
  int bad = 0;
  for (const PvdEntry& entry : entries) {
    const std::vector<NamedSurface> surfaces = read_frame(entry.file);
    std::vector<SurfaceMesh> meshes;
    std::vector<std::string> names;
    for (const NamedSurface& s : surfaces) {
      meshes.push_back({s.x, s.F});
      names.push_back(s.name);
    }
    if (const auto hit = find_intersection(meshes)) {
      ++bad;
      spdlog::error("{} (t = {} s): {}", entry.file.string(), entry.time, describe(SurfaceOverlap(*hit), names));
    }
  }
  if (bad) {
    spdlog::error("{}: {} of {} frames have intersecting triangles", pvd.string(), bad, entries.size());
    return 1;
  }
  spdlog::info("{}: {} frames, no intersecting triangles", pvd.string(), entries.size());
  return 0;
}

}  // namespace stiffsoft
