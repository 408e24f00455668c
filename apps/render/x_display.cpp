#include "x_display.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "program_path.hpp"

namespace stiffsoft {

namespace {

/// Display numbers tried for a private Xvfb (high, to stay clear of real displays and xvfb-run's :99).
constexpr int kFirstDisplay = 90;
constexpr int kLastDisplay = 160;
/// How long Xvfb may take to open its socket.
constexpr auto kStartTimeout = std::chrono::seconds(20);

}  // namespace

XDisplay::XDisplay() {
  if (const char* display = std::getenv("DISPLAY"); display && *display) {
    m_name = display;
    return;
  }
  const auto xvfb = program_path("Xvfb");
  if (!xvfb)
    throw std::runtime_error(
        "no X display ($DISPLAY is not set) and no Xvfb to start one: VTK renders through X11; install Xvfb and "
        "Mesa (apt-get install xvfb libgl1-mesa-dri, or bash scripts/setup.sh) or run under xvfb-run -a");
  for (int n = kFirstDisplay; n <= kLastDisplay; ++n) {
    std::string name = ":";  // (not ":" + …: GCC 12 warns a false -Wrestrict there)
    name += std::to_string(n);
    const std::filesystem::path socket = "/tmp/.X11-unix/X" + std::to_string(n);
    if (std::filesystem::exists("/tmp/.X" + std::to_string(n) + "-lock") || std::filesystem::exists(socket)) continue;
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("cannot start Xvfb: fork failed");
    if (pid == 0) {
      // The child: Xvfb, quiet.
      const std::string null = "/dev/null";
      std::freopen(null.c_str(), "w", stdout);
      std::freopen(null.c_str(), "w", stderr);
      ::execl(xvfb->c_str(), "Xvfb", name.c_str(), "-screen", "0", "1920x1080x24", "-nolisten", "tcp", nullptr);
      ::_exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + kStartTimeout;
    while (std::chrono::steady_clock::now() < deadline) {
      int status = 0;
      if (::waitpid(pid, &status, WNOHANG) == pid) break;  // it lost the race for this number: next
      if (std::filesystem::exists(socket)) {
        m_pid = pid;
        m_name = name;
        ::setenv("DISPLAY", name.c_str(), 1);
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    if (::waitpid(pid, nullptr, WNOHANG) == 0) {  // still running but no socket: give up on it
      ::kill(pid, SIGTERM);
      ::waitpid(pid, nullptr, 0);
    }
  }
  throw std::runtime_error("could not start Xvfb on any display from :" + std::to_string(kFirstDisplay) + " to :" +
                           std::to_string(kLastDisplay));
}

XDisplay::~XDisplay() {
  if (m_pid <= 0) return;
  ::kill(m_pid, SIGTERM);
  ::waitpid(m_pid, nullptr, 0);
  ::unsetenv("DISPLAY");
}

}  // namespace stiffsoft
