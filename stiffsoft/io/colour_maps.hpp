#pragma once
/// @file The colours of a run's pictures, the same in the ParaView script beside the .pvd
/// (io/paraview_script.hpp) and in `stiffsoft render` (apps/render/): soft bodies by von Mises
/// stress, affine bodies by speed, each on a map that is pale at zero (a body at rest stays
/// visible) and dark at the top of its range; fixed and kinematic bodies grey; contact forces red.

#include <array>
#include <vector>

namespace stiffsoft {

/// An RGB colour, components in [0, 1].
using Rgb = std::array<double, 3>;

/// ColorBrewer's YlOrRd (pale yellow → dark red), evenly spaced samples from 0 to the top of
/// the range: von Mises stress of soft bodies.
inline const std::vector<Rgb>& stress_colours() {
  static const std::vector<Rgb> colours{{1.000, 1.000, 0.800}, {1.000, 0.929, 0.627}, {0.996, 0.851, 0.463},
                                        {0.996, 0.698, 0.298}, {0.992, 0.553, 0.235}, {0.988, 0.306, 0.165},
                                        {0.890, 0.102, 0.110}, {0.741, 0.000, 0.149}, {0.502, 0.000, 0.149}};
  return colours;
}

/// ColorBrewer's Blues without its near-white end (pale blue → dark blue), evenly spaced samples
/// from 0 to the top of the range: speed of affine bodies.
inline const std::vector<Rgb>& speed_colours() {
  static const std::vector<Rgb> colours{{0.776, 0.859, 0.937}, {0.620, 0.792, 0.882}, {0.420, 0.682, 0.839},
                                        {0.259, 0.573, 0.776}, {0.129, 0.443, 0.710}, {0.031, 0.318, 0.612},
                                        {0.031, 0.188, 0.420}};
  return colours;
}

/// Fixed and kinematic bodies.
constexpr Rgb kSceneryColour{0.80, 0.80, 0.78};
/// Opacity of fixed and kinematic walls (io/scene_view.hpp, is_wall()).
constexpr double kWallOpacity = 0.3;
/// Contact-force arrows.
constexpr Rgb kArrowColour{0.85, 0.10, 0.10};

/// Where a colour range ends: this quantile of the per-frame largest values over the frames
/// shown, so that one impact's spike does not wash out the rest of the run.
constexpr double kRangeQuantile = 0.9;

}  // namespace stiffsoft
