#pragma once
/// @file Drawing one frame of a run to a PNG, off screen: every body's surface coloured as
/// stiffsoft/io/colour_maps.hpp says, contact forces as arrows drawn over the bodies (so the arrows between
/// two touching bodies stay visible), colour bars and the simulated time.

#include <vtkMultiBlockDataSet.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <stiffsoft/io/scene_view.hpp>

#include "colour_scales.hpp"

namespace stiffsoft {

/// Reads one frame (`frames/NAME_NNNNNN.vtm`) written by `stiffsoft run`; std::runtime_error
/// naming the file when VTK cannot read it.
vtkSmartPointer<vtkMultiBlockDataSet> read_frame_blocks(const std::filesystem::path& vtm);

/// The per-body bounds of a frame, for scene_view().
std::vector<BodyBounds> frame_bounds(vtkMultiBlockDataSet* frame);

/// The names of a frame's walls (is_wall() with the camera's up direction `up`).
std::set<std::string> frame_walls(vtkMultiBlockDataSet* frame, const Eigen::Vector3d& up);

/// An off-screen render window of a fixed size that draws frames with one camera and one set of
/// colour scales (so that the pictures of a series compare). Needs an X display (x_display.hpp).
class FrameRenderer {
 public:
  /// `width`×`height` pixels, the camera `view` fitted to `framed` (framed_box()), colours from
  /// 0 to the tops of `scales`; the blocks named in `walls` are drawn translucent (is_wall()).
  FrameRenderer(int width, int height, const SceneView& view, const Eigen::AlignedBox3d& framed,
                const ColourScales& scales, std::set<std::string> walls);
  /// Draws `frame` (simulated time `time`, s) and writes it to `png`.
  void render(vtkMultiBlockDataSet* frame, double time, const std::filesystem::path& png);

 private:
  double m_arrow_length;  ///< the longest contact-force arrow, m
  ColourScales m_scales;
  std::set<std::string> m_walls;
  vtkSmartPointer<vtkRenderWindow> m_window;
  vtkSmartPointer<vtkRenderer> m_bodies;  ///< layer 0: the bodies, colour bars, time
  vtkSmartPointer<vtkRenderer> m_arrows;  ///< layer 1: contact forces, over the bodies
};

}  // namespace stiffsoft
