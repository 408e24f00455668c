/// @file Loading and meshing are time-bounded: a gmsh script that never ends cannot hang a run.

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "scene_helpers.hpp"

namespace stiffsoft {
namespace {

TEST(LoadTimeout, AnEndlessGeoScriptIsStoppedWithExitCode2AndAnErrorNamingTheScene) {
  const auto out = testing::temporary_folder("endless_script");
  const auto start = std::chrono::steady_clock::now();
  const int code = testing::run_stiffsoft("run " + std::string(STIFFSOFT_SOURCE_DIR) +
                                              "/tests/apps/data/endless_script.json -o " + (out / "run").string() +
                                              " --load-timeout 2",
                                          out / "log.txt");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string log = testing::read_text(out / "log.txt");
  std::printf("exit %d after %.1f s: %s", code, seconds, log.c_str());
  EXPECT_EQ(code, 2) << log;
  EXPECT_NE(log.find("endless_script.json: loading and meshing the scene took longer than 2 s"), std::string::npos)
      << log;
  EXPECT_LT(seconds, 30.0);
  EXPECT_FALSE(std::filesystem::exists(out / "run" / "stats.csv"));
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace stiffsoft
