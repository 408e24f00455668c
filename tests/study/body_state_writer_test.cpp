/// @file bodies.csv (stiffsoft/io/body_state_writer.hpp): the per-body state a study reads, checked on
/// a spinning free box whose state is known in closed form.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <stiffsoft/io/body_state_writer.hpp>
#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene_loader.hpp>
#include <temporary_folder.hpp>

using namespace stiffsoft;

namespace {

std::vector<std::vector<std::string>> read_rows(const std::filesystem::path& file, std::vector<std::string>& header) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::stringstream hs(line);
  for (std::string cell; std::getline(hs, cell, ',');) header.push_back(cell);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> row;
    std::stringstream rs(line);
    for (std::string cell; std::getline(rs, cell, ',');) row.push_back(cell);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

// A 1 × 0.5 × 0.1 m box (1000 kg/m³, 50 kg) spinning at ω = 2 rad/s about z, moving at
// 0.3 m/s along x, beside a fixed floor: every row has the state of both bodies.
TEST(BodyStateWriter, WritesPositionRotationVelocitiesAndEnergy) {
  const std::string json = R"({"description": "spinning box", "gravity": [0, 0, 0],
    "time": {"dt": 0.01, "integrator": "bdf2"}, "solver": {"tolerance": 1e-8},
    "bodies": [{"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [1, 0.1, 1]},
                "position": [0, -2, 0]},
               {"name": "box", "mesh": {"primitive": "box", "size": [1, 0.5, 0.1]}, "kappa": 1e10,
                "velocity": [0.3, 0, 0], "angular_velocity": [0, 0, 2]}]})";
  SceneSimulation run = make_simulation(load_scene_from_string(json, STIFFSOFT_SOURCE_DIR, "spin.json", "spin"), "spin.json");
  Simulation& sim = run.simulation;
  const auto dir = stiffsoft::testing::temporary_folder("bodies_csv");
  {
    BodyStateWriter writer(dir / "bodies.csv");
    writer.add_state(0, sim);
    for (int k = 1; k <= 10; ++k) writer.add_state(sim.step().step, sim);
  }  // the destructor writes the file
  std::vector<std::string> header;
  const auto rows = read_rows(dir / "bodies.csv", header);
  ASSERT_EQ(header, body_state_columns());
  ASSERT_EQ(rows.size(), 22u);  // 11 states × 2 bodies
  auto col = [&](const std::vector<std::string>& row, const std::string& name) {
    return std::stod(row[std::find(header.begin(), header.end(), name) - header.begin()]);
  };
  EXPECT_EQ(rows[0][2], "floor");
  EXPECT_EQ(rows[1][2], "box");
  EXPECT_DOUBLE_EQ(col(rows[0], "py"), -2.0);
  EXPECT_DOUBLE_EQ(col(rows[0], "vx"), 0.0);
  const double m = 1000 * 0.05, Iz = m * (1 + 0.25) / 12;
  for (const int r : {1, 21}) {  // the box at t = 0 and after 10 steps
    const auto& row = rows[r];
    const double t = col(row, "time");
    EXPECT_NEAR(col(row, "px"), 0.3 * t, 1e-9) << "t = " << t;
    EXPECT_NEAR(col(row, "vx"), 0.3, 1e-9);
    EXPECT_NEAR(col(row, "wz"), 2.0, 2e-3) << "t = " << t;  // BDF-2 keeps ω to O((ωh)²)
    // A ≈ R_z(2t): BDF-2's phase error after 10 steps of ωh = 0.02 is ≈ 1e-5 rad.
    EXPECT_NEAR(col(row, "A00"), std::cos(2 * t), 1e-4);
    EXPECT_NEAR(col(row, "A10"), std::sin(2 * t), 1e-4);
    EXPECT_NEAR(col(row, "A22"), 1.0, 1e-6);
    EXPECT_NEAR(col(row, "kinetic_energy"), 0.5 * m * 0.09 + 0.5 * Iz * 4, 2e-3 * (0.5 * Iz * 4));
    EXPECT_DOUBLE_EQ(col(row, "fcy"), 0.0);  // no contact
  }
  EXPECT_DOUBLE_EQ(col(rows[21], "time"), 0.1);
}

// Rows reach the file without a flush once they reach the writer's bound, so a run with few
// frames does not hold every row since its last frame; below the bound nothing is written.
TEST(BodyStateWriter, AppendsItsRowsItselfOnceTheyReachItsBound) {
  const std::string json = R"({"description": "falling box", "time": {"dt": 0.01},
    "bodies": [{"name": "box", "mesh": {"primitive": "box", "size": [1, 0.5, 0.1]}}]})";
  SceneSimulation run =
      make_simulation(load_scene_from_string(json, STIFFSOFT_SOURCE_DIR, "box.json", "box"), "box.json");
  Simulation& sim = run.simulation;
  const auto dir = stiffsoft::testing::temporary_folder("bodies_csv_bound");
  const auto rows_on_disk = [&](const std::filesystem::path& file) {
    std::vector<std::string> header;
    return std::filesystem::exists(file) ? read_rows(file, header).size() : std::size_t(0);
  };
  BodyStateWriter held(dir / "held.csv");  // the default bound: megabytes
  BodyStateWriter bounded(dir / "bounded.csv", 1);  // every state reaches it
  for (int step = 0; step < 3; ++step) {
    if (step > 0) sim.step();
    held.add_state(step, sim);
    bounded.add_state(step, sim);
    EXPECT_FALSE(std::filesystem::exists(dir / "held.csv"));
    EXPECT_EQ(rows_on_disk(dir / "bounded.csv"), std::size_t(step + 1)) << "after step " << step;
  }
  held.flush();
  EXPECT_EQ(rows_on_disk(dir / "held.csv"), 3u);
  const auto text = [](const std::filesystem::path& file) {
    std::ifstream in(file);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(text(dir / "held.csv"), text(dir / "bounded.csv"));  // the same file, however it was written
}
