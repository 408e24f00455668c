#pragma once
/// @file `stiffsoft render DIR/NAME.pvd -o OUT`: pictures of a run (apps/render/).

#include "render/render_options.hpp"

namespace stiffsoft {

/// Renders the frames of `options.pvd` (every `options.every`-th and the last) to
/// OUT/NAME_NNNNNN.png (NNNNNN: the frame's number in the series), writes the contact sheet
/// OUT/NAME_sheet.png and, when asked and ffmpeg is there, OUT/NAME.mp4. Starts a private Xvfb
/// when there is no X display. Returns the exit code (0); throws on unreadable input.
int render_frames(const RenderOptions& options);

}  // namespace stiffsoft
