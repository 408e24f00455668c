#include "render_command.hpp"

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <regex>

#include <stiffsoft/io/frame_reader.hpp>
#include <stiffsoft/io/scene_view.hpp>

#include "render/colour_scales.hpp"
#include "render/contact_sheet.hpp"
#include "render/frame_renderer.hpp"
#include "render/movie.hpp"
#include "render/x_display.hpp"

namespace stiffsoft {

namespace {

/// The scene's gravity from the run's scene.resolved.json beside the .pvd; −y without one.
Eigen::Vector3d run_gravity(const std::filesystem::path& pvd) {
  const std::filesystem::path resolved = pvd.parent_path() / "scene.resolved.json";
  std::ifstream in(resolved);
  if (in) {
    const nlohmann::json scene = nlohmann::json::parse(in, nullptr, false);
    if (scene.is_object() && scene.contains("gravity") && scene["gravity"].is_array() && scene["gravity"].size() == 3)
      return {scene["gravity"][0].get<double>(), scene["gravity"][1].get<double>(), scene["gravity"][2].get<double>()};
  }
  return -Eigen::Vector3d::UnitY();
}

/// The frames to draw: every `every`-th from the first, and the last.
std::vector<int> rendered_frames(int total, int every) {
  std::vector<int> frames;
  for (int k = 0; k < total; k += every) frames.push_back(k);
  if (total > 0 && frames.back() != total - 1) frames.push_back(total - 1);
  return frames;
}

std::string picture_name(const std::string& stem, int frame) {
  char number[16];
  std::snprintf(number, sizeof number, "%06d", frame);
  return stem + "_" + number + ".png";
}

}  // namespace

int render_frames(const RenderOptions& options) {
  const std::vector<PvdEntry> series = read_pvd(options.pvd);
  if (series.empty()) throw std::runtime_error(options.pvd.string() + ": lists no frames");
  const std::string stem = options.pvd.stem().string();
  const std::vector<int> frames = rendered_frames(int(series.size()), std::max(1, options.every));
  std::filesystem::create_directories(options.out);
  // Pictures of an earlier rendering would mix into the movie.
  const std::regex earlier(std::regex_replace(stem, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") + R"(_\d{6}\.png)");
  for (const auto& entry : std::filesystem::directory_iterator(options.out))
    if (std::regex_match(entry.path().filename().string(), earlier)) std::filesystem::remove(entry.path());

  // One pass over the frames for the colour ranges and the box the camera frames.
  ColourScales scales;
  std::vector<BodyBounds> bounds;
  for (int k : frames) {
    const auto frame = read_frame_blocks(series[k].file);
    scales.extend(frame);
    for (const BodyBounds& b : frame_bounds(frame)) bounds.push_back(b);
  }
  const auto first = read_frame_blocks(series.front().file);
  const SceneView view = scene_view(run_gravity(options.pvd));

  const XDisplay display;
  if (display.started())
    spdlog::info("no X display ($DISPLAY unset): rendering under a private Xvfb on {} (stopped when done)", display.name());
  FrameRenderer renderer(options.width, options.height, view, framed_box(bounds, view), scales,
                         frame_walls(first, view.up));
  std::vector<std::filesystem::path> pictures;
  const auto start = std::chrono::steady_clock::now();
  auto last_report = start;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const int k = frames[i];
    pictures.push_back(options.out / picture_name(stem, k));
    renderer.render(read_frame_blocks(series[k].file), series[k].time, pictures.back());
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_report).count() > 2.0 || i + 1 == frames.size()) {
      const double elapsed = std::chrono::duration<double>(now - start).count();
      spdlog::info("rendered {}/{} frames  t={:.3f} s  ETA {:.0f} s", i + 1, frames.size(), series[k].time,
                   elapsed / double(i + 1) * double(frames.size() - i - 1));
      last_report = now;
    }
  }

  std::vector<std::filesystem::path> sheet_pictures;
  for (int pick : sheet_picks(int(pictures.size()), options.sheet_frames)) sheet_pictures.push_back(pictures[pick]);
  const std::filesystem::path sheet = options.out / (stem + "_sheet.png");
  write_contact_sheet(sheet_pictures, options.sheet_columns, options.sheet_scale, sheet);
  spdlog::info("wrote {} pictures {}x{} to {}; contact sheet {}", pictures.size(), options.width, options.height,
               options.out.string(), sheet.string());
  if (options.movie) {
    if (const auto movie = write_movie(options.out, stem, options.fps))
      spdlog::info("movie: {}", movie->string());
    else
      spdlog::warn("no movie: ffmpeg is not installed (apt-get install ffmpeg)");
  }
  return 0;
}

}  // namespace stiffsoft
