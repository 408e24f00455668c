#include "x_display.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "program_path.hpp"

namespace stiffsoft {

namespace {

/// Display numbers tried for a private Xvfb (high, to stay clear of real displays and xvfb-run's :99).
constexpr int kFirstDisplay = 90;
constexpr int kLastDisplay = 160;
/// How long Xvfb may take to report its display number (it is then accepting connections).
constexpr auto kStartTimeout = std::chrono::seconds(20);

/// True when Xvfb wrote its display number and the newline after it to `fd` within
/// kStartTimeout (the pipe must stay open until both are written: Xvfb writes them apart and
/// dies if the second write fails); false when it closed the pipe first (it exited) or took
/// too long.
bool wait_for_display_number(int fd) {
  const auto deadline = std::chrono::steady_clock::now() + kStartTimeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd watch{fd, POLLIN, 0};
    const int polled = ::poll(&watch, 1, static_cast<int>(left.count()));
    if (polled < 0 && errno == EINTR) continue;
    if (polled <= 0) return false;
    char c = 0;
    const ssize_t got = ::read(fd, &c, 1);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    if (c == '\n') return true;
  }
}

/// True when an X server accepts connections on display n's socket: the abstract one
/// (@/tmp/.X11-unix/Xn, which Linux keeps per network namespace, so a server of another
/// container on the same host can hold it with no lock file in our /tmp) or the file one.
/// Clients try the abstract socket first, so a display whose abstract socket another server
/// answers is not ours to take even when our Xvfb starts on it (it then listens on the file only).
bool someone_serves(int n) {
  const std::string path = "/tmp/.X11-unix/X" + std::to_string(n);
  for (const bool abstract : {true, false}) {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) return false;
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::size_t offset = abstract ? 1 : 0;  // abstract: a leading NUL byte
    std::memcpy(address.sun_path + offset, path.data(), path.size());
    const auto length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + offset + path.size());
    const bool answered = ::connect(fd, reinterpret_cast<const sockaddr*>(&address), length) == 0;
    ::close(fd);
    if (answered) return true;
  }
  return false;
}

}  // namespace

XDisplay::XDisplay(const std::filesystem::path& xvfb_log) {
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
    if (std::filesystem::exists("/tmp/.X" + std::to_string(n) + "-lock") || someone_serves(n)) continue;
    // Xvfb writes the display number to -displayfd once it accepts connections, and only the
    // Xvfb that holds the display's lock gets that far: one that lost the number to another
    // process (a parallel test, another render) exits and closes the pipe instead. Watching
    // the socket appear cannot tell the two apart.
    int ready[2];
    if (::pipe(ready) != 0) throw std::runtime_error("cannot start Xvfb: pipe failed");
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("cannot start Xvfb: fork failed");
    if (pid == 0) {
      // The child: Xvfb, quiet, and stopped with us even when we are killed or interrupted.
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);
      ::close(ready[0]);
      const std::string log = xvfb_log.empty() ? "/dev/null" : xvfb_log.string();
      std::freopen(log.c_str(), "a", stdout);
      std::freopen(log.c_str(), "a", stderr);
      const std::string fd = std::to_string(ready[1]);
      // -noreset: an X server resets when its last client disconnects and hangs up on the
      // clients that connect meanwhile. pvbatch connects once, disconnects and connects again
      // at once, so on a loaded machine its second connection met the reset ("bad X server
      // connection": 5 of 10 runs beside two busy simulations, 0 of 14 with -noreset).
      ::execl(xvfb->c_str(), "Xvfb", name.c_str(), "-displayfd", fd.c_str(), "-screen", "0", "1920x1080x24",
              "-nolisten", "tcp", "-noreset", nullptr);
      ::_exit(127);
    }
    ::close(ready[1]);
    const bool serving = wait_for_display_number(ready[0]);
    ::close(ready[0]);
    if (serving) {
      m_pid = pid;
      m_name = name;
      ::setenv("DISPLAY", name.c_str(), 1);
      return;
    }
    ::kill(pid, SIGTERM);  // lost the number, or hung: next
    ::waitpid(pid, nullptr, 0);
  }
  throw std::runtime_error("could not start Xvfb on any display from :" + std::to_string(kFirstDisplay) + " to :" +
                           std::to_string(kLastDisplay));
}

bool XDisplay::running() {
  if (m_pid <= 0 || m_exited) return !m_exited;
  m_exited = ::waitpid(m_pid, nullptr, WNOHANG) == m_pid;
  return !m_exited;
}

XDisplay::~XDisplay() {
  if (m_pid <= 0) return;
  if (!m_exited) {
    ::kill(m_pid, SIGTERM);
    ::waitpid(m_pid, nullptr, 0);
  }
  ::unsetenv("DISPLAY");
}

}  // namespace stiffsoft
