/// @file `stiffsoft study` end to end on two small studies (three values each): the observed
/// orders match theory, the report files are written, a re-run takes every run from the cache,
/// and bad input exits with code 2. The full studies (studies/*.json) are not tests.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "scene_helpers.hpp"

using namespace stiffsoft::testing;

namespace {

/// A value of orders.csv: column `column` of the row whose quantity and series match.
std::string order_cell(const std::filesystem::path& file, const std::string& series, const std::string& column) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  {
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) header.push_back(cell);
  }
  const auto col = std::size_t(std::find(header.begin(), header.end(), column) - header.begin());
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (cells.size() > col && cells[1] == series) return cells[col];
  }
  return "";
}

void expect_nonempty(const std::filesystem::path& file) {
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  EXPECT_GT(std::filesystem::file_size(file), 0u) << file;
}

std::filesystem::path write_study(const std::filesystem::path& dir, const std::string& text) {
  const auto file = dir / "study.json";
  std::ofstream(file) << text;
  return file;
}

const std::string kScenes = STIFFSOFT_SOURCE_DIR "/studies/scenes/";

}  // namespace

// Backward Euler is first order, BDF-2 second order on the steady rotation of a free box
// (studies/be_vs_bdf2.json with three time steps).
TEST(Study, BackwardEulerAndBdf2OrdersOnFreeRotation) {
  const auto dir = temporary_folder("study_orders");
  const auto file = write_study(dir, R"({
    "scene": ")" + kScenes + R"(spinning_box.json",
    "sweep": [{"path": "/time/dt", "values": [0.005, 0.0025, 0.00125]},
              {"path": "/time/integrator", "values": ["backward_euler", "bdf2"]}],
    "constants": {"omega": 6.283185307179586},
    "quantities": [{"name": "orientation at 1 s", "body": "box", "field": "affine_matrix", "at": 1.0,
                    "reference": {"builtin": "steady_rotation_z"}, "expected_order": {"backward_euler": 1, "bdf2": 2}}]})");
  const auto out = dir / "out";
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(run_stiffsoft("study " + file.string() + " -o " + out.string(), dir / "log.txt"), 0) << read_text(dir / "log.txt");
  const double first = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double be = std::stod(order_cell(out / "orders.csv", "backward_euler", "slope"));
  const double bdf2 = std::stod(order_cell(out / "orders.csv", "bdf2", "slope"));
  std::printf("observed orders: BE %.3f, BDF-2 %.3f (study %.1f s)\n", be, bdf2, first);
  EXPECT_NEAR(be, 1.0, 0.2);
  EXPECT_NEAR(bdf2, 2.0, 0.25);
  EXPECT_EQ(order_cell(out / "orders.csv", "backward_euler", "agrees"), "1");
  EXPECT_EQ(order_cell(out / "orders.csv", "bdf2", "agrees"), "1");
  for (const char* f : {"study.csv", "orders.csv", "report.md", "orientation_at_1_s_error.png",
                        "orientation_at_1_s_frontier.png"})
    expect_nonempty(out / f);
  // Every run converged and every frame is intersection-free.
  for (double v : csv_column(out / "study.csv", "converged")) EXPECT_EQ(v, 1.0);
  for (double v : csv_column(out / "study.csv", "intersection_free")) EXPECT_EQ(v, 1.0);
  // Re-running finds every run in the cache.
  ASSERT_EQ(run_stiffsoft("study " + file.string() + " -o " + out.string(), dir / "log2.txt"), 0) << read_text(dir / "log2.txt");
  const std::vector<double> cached = csv_column(out / "study.csv", "cached");
  ASSERT_EQ(cached.size(), 6u);
  for (double v : cached) EXPECT_EQ(v, 1.0);
}

// The rigidity error of a spinning affine body falls as stress / κ (slope −1 against κ).
TEST(Study, RigidityErrorFallsAsOneOverKappa) {
  const auto dir = temporary_folder("study_kappa");
  const auto file = write_study(dir, R"({
    "scene": ")" + kScenes + R"(spinning_box.json",
    "set": {"/time/integrator": "bdf2", "/time/duration": 0.5},
    "sweep": [{"path": "/bodies/0/kappa", "values": [1e7, 1e8, 1e9]}],
    "quantities": [{"name": "rigidity error", "stats": "orthogonality_error", "reduce": "max",
                    "reference": {"analytic": "0"}, "expected_order": -1}]})");
  const auto out = dir / "out";
  ASSERT_EQ(run_stiffsoft("study " + file.string() + " -o " + out.string() + " --jobs 2", dir / "log.txt"), 0)
      << read_text(dir / "log.txt");
  const double slope = std::stod(order_cell(out / "orders.csv", "", "slope"));
  std::printf("rigidity error against kappa: slope %.3f\n", slope);
  EXPECT_NEAR(slope, -1.0, 0.1);
  for (const char* f : {"study.csv", "report.md", "rigidity_error_error.png", "rigidity_error_frontier.png"})
    expect_nonempty(out / f);
}

// Bad input exits with 2 and names the study file and the JSON path; no run starts.
TEST(Study, BadInputExitsWithTwo) {
  const auto dir = temporary_folder("study_bad");
  const auto file = write_study(dir, R"({
    "scene": ")" + kScenes + R"(spinning_box.json",
    "sweep": [{"path": "/time/step", "values": [0.01]}],
    "quantities": [{"name": "q", "stats": "kappa", "reference": {"analytic": "0"}}]})");
  EXPECT_EQ(run_stiffsoft("study " + file.string() + " -o " + (dir / "out").string(), dir / "log.txt"), 2);
  const std::string log = read_text(dir / "log.txt");
  EXPECT_NE(log.find("study.json: /sweep/0/values/0"), std::string::npos) << log;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "runs"));
  const auto missing = write_study(dir, R"({"scene": "none.json", "sweep": [{"path": "/time/dt", "values": [0.01]}],
    "quantities": [{"name": "q", "stats": "kappa", "reference": {"analytic": "0"}}]})");
  EXPECT_EQ(run_stiffsoft("study " + missing.string() + " -o " + (dir / "out").string(), dir / "log.txt"), 2);
}
