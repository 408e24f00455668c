/// @file `stiffsoft render`: pictures of a short run of the default scene are written, have the
/// asked size, are not one flat colour and show affine and soft bodies in their colours; the
/// contact sheet too; without a display it starts Xvfb (or says what to install).

#include <gtest/gtest.h>

#include "picture_checks.hpp"
#include "apps/scene_helpers.hpp"

using namespace stiffsoft::testing;
namespace fs = std::filesystem;

namespace {

/// Is `name` an executable on the PATH?
bool on_path(const std::string& name) { return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0; }

}  // namespace

TEST(Render, WritesPicturesAndAContactSheetThatShowTheBodies) {
  const fs::path out = temporary_folder("stiffsoft_render");
  const fs::path scene = fs::path(STIFFSOFT_SOURCE_DIR) / "scenes/default.json";
  ASSERT_EQ(run_stiffsoft("run " + scene.string() + " -o " + out.string() + " --steps 30", out / "run.log"), 0)
      << read_text(out / "run.log");
  // No display: the command starts its own Xvfb (the way a server or CI runs it).
  const int status = run_stiffsoft("render " + (out / "default.pvd").string() + " -o " + (out / "png").string() +
                                       " --every 5 --size 320x180 --mp4",
                                   out / "render.log");
  const std::string log = read_text(out / "render.log");
  if (!on_path("Xvfb") && !std::getenv("DISPLAY")) {
    EXPECT_NE(status, 0);
    EXPECT_NE(log.find("xvfb"), std::string::npos) << log;
    GTEST_SKIP() << "no X display and no Xvfb (apt-get install xvfb libgl1-mesa-dri): " << log;
  }
  ASSERT_EQ(status, 0) << log;
  // 30 steps of 0.01 s, a frame every 0.02 s: frames 0..15, every 5th: 0, 5, 10, 15.
  for (const char* frame : {"000000", "000005", "000010", "000015"}) {
    const fs::path png = out / "png" / (std::string("default_") + frame + ".png");
    ASSERT_TRUE(fs::exists(png)) << png << "\n" << log;
    EXPECT_GT(fs::file_size(png), 1000u) << png;
    const PictureSummary s = summarize_picture(png);
    EXPECT_EQ(s.width, 320) << png;
    EXPECT_EQ(s.height, 180) << png;
    EXPECT_GT(s.colours, 100u) << png << " is (nearly) one flat colour";
    EXPECT_GT(s.bluish, 200u) << png << ": no affine body in its speed colours";
    EXPECT_GT(s.warm, 100u) << png << ": no soft body in its stress colours";
  }
  EXPECT_FALSE(fs::exists(out / "png" / "default_000003.png"));
  const PictureSummary sheet = summarize_picture(out / "png" / "default_sheet.png");
  EXPECT_EQ(sheet.width, 3 * 160 + 4 * 4);  // 3 columns of half-size tiles, 4 px gaps
  EXPECT_EQ(sheet.height, 2 * 90 + 3 * 4);  // 4 frames: 2 rows
  EXPECT_GT(sheet.colours, 100u);
  if (on_path("ffmpeg")) {
    ASSERT_TRUE(fs::exists(out / "png" / "default.mp4")) << log;
    EXPECT_GT(fs::file_size(out / "png" / "default.mp4"), 1000u);
  } else {
    EXPECT_NE(log.find("ffmpeg is not installed"), std::string::npos) << log;
  }
  fs::remove_all(out);
}

TEST(Render, RefusesABadSizeAndAMissingSeries) {
  const fs::path out = temporary_folder("stiffsoft_render_bad");
  EXPECT_NE(run_stiffsoft("render " + (out / "none.pvd").string() + " -o " + out.string() + " --size 12", out / "a.log"), 0);
  EXPECT_NE(read_text(out / "a.log").find("WIDTHxHEIGHT"), std::string::npos) << read_text(out / "a.log");
  EXPECT_NE(run_stiffsoft("render " + (out / "none.pvd").string() + " -o " + out.string(), out / "b.log"), 0);
  EXPECT_NE(read_text(out / "b.log").find("none.pvd"), std::string::npos) << read_text(out / "b.log");
  fs::remove_all(out);
}
