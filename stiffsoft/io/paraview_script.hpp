#pragma once
/// @file The ParaView script written beside every run's .pvd (`NAME.paraview.py`): it opens the
/// series ready to look at (ParaView 5.11, Debian's): soft bodies coloured by von Mises stress,
/// affine bodies by speed, fixed and kinematic bodies grey, contact forces as red arrows (the
/// colours and ranges of io/colour_maps.hpp, as `stiffsoft render` draws them), the camera of
/// io/scene_view.hpp and the simulated time in a corner.
///
///     paraview --script=out/default.paraview.py                  # the GUI, ready to play
///     pvbatch out/default.paraview.py --screenshot last.png      # headless: the last frame

#include <filesystem>
#include <string>
#include <vector>

#include <stiffsoft/io/frame_writer.hpp>
#include <stiffsoft/io/scene_view.hpp>

namespace stiffsoft {

/// What the script shows.
struct ParaViewScene {
  std::string pvd_name;                ///< the series' file name, beside the script (NAME.pvd)
  std::vector<std::string> soft;       ///< block names of the soft bodies
  std::vector<std::string> affine;     ///< block names of the affine bodies
  std::vector<std::string> scenery;    ///< block names of the fixed and kinematic bodies but walls
  std::vector<std::string> walls;      ///< block names of the fixed and kinematic walls (is_wall()), translucent
  SceneView view;                      ///< the camera rule (the script fits it to the frames)
};

/// The script's content for a run named `name` (its series is `name`.pvd) whose first frame is
/// `bodies`, under `gravity` (m/s²): the bodies sorted by model (walls by is_wall() in that
/// frame), the view of scene_view().
ParaViewScene paraview_scene(const std::string& name, const std::vector<BodyFrame>& bodies,
                             const Eigen::Vector3d& gravity);

/// `OUT/NAME.paraview.py`, the script's place beside `OUT/NAME.pvd`.
std::filesystem::path paraview_script_path(const std::filesystem::path& out, const std::string& name);

/// The script's text (Python 3, `from paraview.simple import *`). It finds the .pvd beside
/// itself, so the output folder can be moved. The colour ranges are taken from the frames when
/// the script runs (kRangeQuantile of the per-frame largest values).
std::string paraview_script(const ParaViewScene& scene);

/// Writes paraview_script(scene) to `file`, atomically.
void write_paraview_script(const std::filesystem::path& file, const ParaViewScene& scene);

}  // namespace stiffsoft
