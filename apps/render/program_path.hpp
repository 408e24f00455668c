#pragma once
/// @file Finding an external program (Xvfb, ffmpeg) on the PATH.

#include <filesystem>
#include <optional>
#include <string>

namespace stiffsoft {

/// The first executable file called `name` in a folder of $PATH, or nothing.
std::optional<std::filesystem::path> program_path(const std::string& name);

}  // namespace stiffsoft
