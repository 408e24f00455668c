/// @file The ParaView script beside every run's .pvd (stiffsoft/io/paraview_script.hpp) runs in
/// ParaView's own pvbatch 5.11 and draws the run coloured: affine bodies blue, soft bodies
/// yellow to red. pvbatch comes from $STIFFSOFT_PVBATCH, the PATH, or build/paraview-aside
/// (scripts/paraview_aside.sh); without one the test is skipped and says why. Also the private
/// Xvfb its retry relies on: a second one takes another display while the first runs.

#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <memory>

#include "apps/render/x_display.hpp"
#include "picture_checks.hpp"
#include "apps/scene_helpers.hpp"

using namespace stiffsoft::testing;
namespace fs = std::filesystem;

namespace {

bool on_path(const std::string& name) { return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0; }

/// The pvbatch to test with, or "".
std::string find_pvbatch() {
  if (const char* given = std::getenv("STIFFSOFT_PVBATCH"); given && *given) return given;
  if (on_path("pvbatch")) return "pvbatch";
  const fs::path aside = fs::path(STIFFSOFT_SOURCE_DIR) / "build/paraview-aside/pvbatch";
  return fs::exists(aside) ? aside.string() : std::string();
}

}  // namespace

TEST(XDisplay, ASecondPrivateXvfbTakesAnotherDisplayWhileTheFirstRuns) {
  // What the retry below relies on: with the failed display still running, a new one is fresh.
  if (!on_path("Xvfb")) GTEST_SKIP() << "no Xvfb (apt-get install xvfb)";
  const char* given = std::getenv("DISPLAY");
  const std::string saved = given ? given : "";
  ::unsetenv("DISPLAY");
  {
    const stiffsoft::XDisplay first;
    ASSERT_TRUE(first.started());
    ::unsetenv("DISPLAY");
    const stiffsoft::XDisplay second;
    ASSERT_TRUE(second.started());
    EXPECT_NE(first.name(), second.name());
  }
  if (!saved.empty()) ::setenv("DISPLAY", saved.c_str(), 1);
}

TEST(ParaViewScript, OpensTheRunColouredInPvbatch) {
  const std::string pvbatch = find_pvbatch();
  if (pvbatch.empty())
    GTEST_SKIP() << "no pvbatch: Debian's python3-paraview conflicts with python3-vtk9, which libvtk9-dev needs; "
                    "`bash scripts/paraview_aside.sh` unpacks ParaView 5.11 into build/paraview-aside for this test";
  // pvbatch renders through X11 too: the display stiffsoft render would use (a private Xvfb
  // without one; xvfb-run -a proved racy on a loaded machine).
  if (!on_path("Xvfb") && !std::getenv("DISPLAY"))
    GTEST_SKIP() << "no X display and no Xvfb for pvbatch (apt-get install xvfb libgl1-mesa-dri)";
  const fs::path out = temporary_folder("stiffsoft_paraview");
  const fs::path scene = fs::path(STIFFSOFT_SOURCE_DIR) / "scenes/default.json";
  ASSERT_EQ(run_stiffsoft("run " + scene.string() + " -o " + out.string() + " --steps 20", out / "run.log"), 0)
      << read_text(out / "run.log");
  const fs::path script = out / "default.paraview.py";
  ASSERT_TRUE(fs::exists(script));
  const fs::path png = out / "last.png";
  const std::string command = pvbatch + " " + script.string() +
                              " --screenshot " + png.string() + " > " + (out / "pvbatch.log").string() + " 2>&1";
  // CI twice saw pvbatch fail to connect ("bad X server connection") to an Xvfb that had
  // reported itself ready, on the first display number tried (:99 under xvfb-run, :90 here);
  // never reproduced on this machine. One possible cause, now avoided by XDisplay: another
  // server answering that display's abstract socket, which clients try first and which a
  // lock file in our /tmp does not reveal. A connection failure is still retried once on a
  // fresh display, saying so with what Xvfb printed; any other failure is not. The failed
  // display is kept until the test ends, so that the retry's Xvfb takes another number (session
  // 29 saw both attempts fail on :90 on a loaded machine, the second one started on the number
  // the first had just freed).
  std::unique_ptr<stiffsoft::XDisplay> failed;
  for (int attempt = 1;; ++attempt) {
    const fs::path xvfb_log = out / ("xvfb_" + std::to_string(attempt) + ".log");
    // With Xvfb present, failing to start it is a failure, not a skip.
    auto display = std::make_unique<stiffsoft::XDisplay>(xvfb_log);
    const int status = std::system(command.c_str());
    const std::string log = read_text(out / "pvbatch.log");
    const bool no_connection = log.find("bad X server connection") != std::string::npos;
    const std::string about_x = "display " + display->name() + (display->started() ? " (private Xvfb, " : " (") +
                                (display->running() ? "still running" : "gone") + "); Xvfb printed:\n" +
                                read_text(xvfb_log);
    if (status != 0 && no_connection && attempt == 1) {
      std::cerr << "pvbatch could not connect to " << about_x << "\nretrying on a fresh display\n";
      failed = std::move(display);
      ::unsetenv("DISPLAY");  // the next XDisplay starts its own Xvfb instead of taking this one
      continue;
    }
    ASSERT_EQ(status, 0) << log << "\n" << about_x;
    break;
  }
  const std::string log = read_text(out / "pvbatch.log");
  EXPECT_EQ(log.find("Traceback"), std::string::npos) << log;
  ASSERT_TRUE(fs::exists(png)) << log;
  const PictureSummary s = summarize_picture(png);
  EXPECT_EQ(s.width, 960);
  EXPECT_EQ(s.height, 540);
  EXPECT_GT(s.colours, 100u) << "one flat colour";
  EXPECT_GT(s.bluish, 1000u) << "no affine body in its speed colours";
  EXPECT_GT(s.warm, 500u) << "no soft body in its stress colours";
  fs::remove_all(out);
}
