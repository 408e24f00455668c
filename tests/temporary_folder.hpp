#pragma once
/// @file Scratch folders of the tests under the system's temporary directory, removed with
/// everything in them when the test program exits, so that runs of the suite leave nothing
/// behind.

#include <filesystem>
#include <random>
#include <string>
#include <system_error>
#include <vector>

namespace stiffsoft::testing {

/// A fresh empty folder named `stem`_<random> under the system's temporary directory, removed
/// with its contents when the test program exits.
inline std::filesystem::path temporary_folder(const std::string& stem) {
  struct Folders {
    std::vector<std::filesystem::path> made;
    ~Folders() {
      for (const auto& folder : made) {
        std::error_code ignored;  // a folder already gone, or not ours to remove
        std::filesystem::remove_all(folder, ignored);
      }
    }
  };
  static Folders folders;
  std::random_device rd;
  const auto dir = std::filesystem::temp_directory_path() / (stem + "_" + std::to_string(rd()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  folders.made.push_back(dir);
  return dir;
}

}  // namespace stiffsoft::testing
