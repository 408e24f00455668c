#pragma once
/// @file `stiffsoft check DIR/NAME.pvd`: exact intersection check of written frames.

#include <filesystem>

namespace stiffsoft {

/// Checks every frame of the series for a pair of intersecting triangles of different bodies
/// (exact predicates). Returns 0 when none intersect, 1 otherwise (naming frame, bodies, faces).
int check_frames(const std::filesystem::path& pvd);

}  // namespace stiffsoft
