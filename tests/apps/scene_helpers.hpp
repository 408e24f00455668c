#pragma once
/// @file Helpers of the scene-level tests: inline JSON scenes run through the library, and
/// the `stiffsoft` binary run on scene files.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene_loader.hpp>
#include <temporary_folder.hpp>

namespace stiffsoft::testing {

/// A simulation of an inline JSON scene (relative defaults resolved as `stiffsoft run` does).
inline Simulation simulate(const std::string& json, const std::string& name = "inline") {
  PreparedScene p = prepare_scene(load_scene_from_string(json, STIFFSOFT_SOURCE_DIR, name + ".json", name), name + ".json");
  return Simulation(std::move(p.model), p.settings);
}

/// Runs the stiffsoft binary with `args`; returns its exit code; output goes to `log`.
inline int run_stiffsoft(const std::string& args, const std::filesystem::path& log) {
  const std::string cmd = std::string(STIFFSOFT_BINARY) + " " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The whole content of a text file.
inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Column `column` of a CSV file with a header row, as numbers.
inline std::vector<double> csv_column(const std::filesystem::path& file, const std::string& column) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  std::string cell;
  int index = -1;
  for (int i = 0; std::getline(header, cell, ','); ++i)
    if (cell == column) index = i;
  std::vector<double> values;
  if (index < 0) return values;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    for (int i = 0; std::getline(row, cell, ','); ++i)
      if (i == index) values.push_back(std::stod(cell));
  }
  return values;
}

}  // namespace stiffsoft::testing
