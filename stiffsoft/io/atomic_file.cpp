#include <stiffsoft/io/atomic_file.hpp>

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace stiffsoft {

namespace {

/// A temporary name in the folder of `path`: same folder so that rename is a single atomic
/// directory update (rename across file systems would fail); pid + counter so that two writers
/// (threads or processes) of the same file never share a temporary.
std::filesystem::path temporary_name(const std::filesystem::path& path) {
  static std::atomic<unsigned long> counter{0};
  // Appended piecewise: `"." + std::string` trips a GCC 12 -Wrestrict false positive.
  std::string name = ".";
  name += path.filename().string();
  name += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1));
  return path.parent_path() / name;
}

void remove_quietly(const std::filesystem::path& p) {
  std::error_code ignored;
  std::filesystem::remove(p, ignored);
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  if (path.filename().empty()) {
    throw std::runtime_error("cannot write '" + path.string() + "': not a file name");
  }
  const std::filesystem::path tmp = temporary_name(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw std::runtime_error("cannot write '" + path.string() + "': cannot create temporary file '" +
                               tmp.string() + "' (missing or unwritable folder?)");
    }
    try {
      write(out);
    } catch (...) {
      out.close();
      remove_quietly(tmp);
      throw;
    }
    // A full disk shows up as badbit on a write or on the final flush/close, not earlier.
    out.flush();
    const bool written = out.good();
    out.close();
    if (!written || out.fail()) {
      remove_quietly(tmp);
      throw std::runtime_error("cannot write '" + path.string() +
                               "': write to temporary file failed (disk full or I/O error)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    remove_quietly(tmp);
    throw std::runtime_error("cannot write '" + path.string() + "': rename from '" + tmp.string() +
                             "' failed: " + ec.message());
  }
}

int remove_stale_temporaries(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> stale;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(folder, ec); !ec && it != std::filesystem::end(it); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (it->is_regular_file() && name.size() > 1 && name[0] == '.' && name.find(".tmp.") != std::string::npos)
      stale.push_back(it->path());
  }
  for (const std::filesystem::path& file : stale) std::filesystem::remove(file, ec);
  return int(stale.size());
}

}  // namespace stiffsoft
