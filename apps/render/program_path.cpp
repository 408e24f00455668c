#include "program_path.hpp"

#include <unistd.h>

#include <cstdlib>
#include <sstream>

namespace stiffsoft {

std::optional<std::filesystem::path> program_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "");
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (folder.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(folder) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

}  // namespace stiffsoft
