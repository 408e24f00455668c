#pragma once
/// @file A movie of rendered frames, with ffmpeg when it is installed.

#include <filesystem>
#include <optional>
#include <string>

namespace stiffsoft {

/// Encodes `folder`/`stem`_*.png (in name order) at `fps` frames per second into
/// `folder`/`stem`.mp4 (H.264, yuv420p) with ffmpeg. Returns the movie's path, or nothing when
/// ffmpeg is not on the PATH; std::runtime_error when ffmpeg fails.
std::optional<std::filesystem::path> write_movie(const std::filesystem::path& folder, const std::string& stem, int fps);

}  // namespace stiffsoft
