#include "movie.hpp"

#include <cstdlib>
#include <stdexcept>

#include "program_path.hpp"

namespace stiffsoft {

namespace {

/// `text` in single quotes for /bin/sh.
std::string quoted(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

std::optional<std::filesystem::path> write_movie(const std::filesystem::path& folder, const std::string& stem, int fps) {
  const auto ffmpeg = program_path("ffmpeg");
  if (!ffmpeg) return std::nullopt;
  const std::filesystem::path movie = folder / (stem + ".mp4");
  // Even width and height: yuv420p needs them.
  const std::string command = quoted(ffmpeg->string()) + " -loglevel error -y -framerate " + std::to_string(fps) +
                              " -pattern_type glob -i " + quoted((folder / (stem + "_[0-9]*.png")).string()) +
                              " -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' -c:v libx264 -pix_fmt yuv420p " +
                              quoted(movie.string()) + " < /dev/null";
  if (std::system(command.c_str()) != 0) throw std::runtime_error("ffmpeg failed to write " + movie.string());
  return movie;
}

}  // namespace stiffsoft
