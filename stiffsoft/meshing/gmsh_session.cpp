#include <stiffsoft/meshing/gmsh_session.hpp>

#include <gmsh.h>

#include <atomic>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace stiffsoft {
namespace {

std::mutex gmsh_mutex;
std::atomic<std::size_t> session_count{0};
thread_local bool inside_session = false;

/// Holds the lock and the initialized gmsh for one session.
class GmshSession {
 public:
  explicit GmshSession(bool verbose) : lock_(gmsh_mutex) {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    try {
      gmsh::option::setNumber("General.Terminal", verbose ? 1 : 0);
      gmsh::option::setNumber("General.NumThreads", 1);
      gmsh::logger::start();
    } catch (...) {
      gmsh::finalize();
      throw;
    }
    inside_session = true;
    ++session_count;
  }
  ~GmshSession() {
    inside_session = false;
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) {
      // A destructor must not throw; a failing finalize leaves nothing we could clean up.
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  std::lock_guard<std::mutex> lock_;
};

}  // namespace

void run_gmsh(const std::string& what, bool verbose, const std::function<void()>& body) {
  if (inside_session) throw std::logic_error(what + ": run_gmsh called inside a running gmsh session");
  try {
    GmshSession session(verbose);
    try {
      body();
    } catch (const std::string& message) {
      // Read the log while the session is still alive: the thrown text may be empty.
      const std::string logged = gmsh_logged_errors();
      throw std::runtime_error(what + ": gmsh: " + (message.empty() ? logged : message));
    }
  } catch (const std::string& message) {
    // thrown by gmsh::initialize or an option in the session's constructor
    throw std::runtime_error(what + ": gmsh: " + message);
  }
}

std::string gmsh_logged_errors() {
  std::vector<std::string> log;
  gmsh::logger::get(log);
  std::string errors;
  for (const auto& line : log)
    if (line.rfind("Error", 0) == 0) errors += (errors.empty() ? "" : "; ") + line;
  return errors;
}

std::size_t gmsh_session_count() { return session_count.load(); }

}  // namespace stiffsoft
