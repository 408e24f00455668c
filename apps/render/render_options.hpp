#pragma once
/// @file The settings of `stiffsoft render` (apps/render_command.hpp).

#include <filesystem>

namespace stiffsoft {

/// What `stiffsoft render DIR/NAME.pvd -o OUT` draws and writes.
struct RenderOptions {
  std::filesystem::path pvd;  ///< the series written by `stiffsoft run`
  std::filesystem::path out;  ///< folder of the pictures: OUT/NAME_NNNNNN.png, OUT/NAME_sheet.png, OUT/NAME.mp4
  int every = 1;              ///< render every N-th frame of the series (the last frame always)
  int width = 960;            ///< picture width, pixels
  int height = 540;           ///< picture height, pixels
  int sheet_frames = 6;       ///< frames on the contact sheet, evenly spaced from first to last
  int sheet_columns = 3;      ///< columns of the contact sheet
  double sheet_scale = 0.5;   ///< size of a contact-sheet tile relative to a picture
  bool movie = false;         ///< also write OUT/NAME.mp4 with ffmpeg (skipped, with a message, without it)
  int fps = 30;               ///< frames per second of the movie
};

}  // namespace stiffsoft
