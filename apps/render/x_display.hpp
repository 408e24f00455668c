#pragma once
/// @file An X display to render on. Debian's VTK 9.1 renders through X11 (GLX), also off
/// screen, so a machine without a display (a server, CI, a container) needs a virtual one:
/// Xvfb with Mesa's software OpenGL (llvmpipe), both installed by scripts/setup.sh.

#include <sys/types.h>

#include <filesystem>
#include <string>

namespace stiffsoft {

/// Makes sure $DISPLAY names a display while it lives: the one already set, or a private Xvfb
/// started on the first free display number from :90 up (no lock file, no server answering its
/// sockets; safe against parallel starts) and stopped (SIGTERM) when this object
/// goes. Throws std::runtime_error with what to install when there is no display and no Xvfb.
class XDisplay {
 public:
  /// `xvfb_log`, when given, receives what a started Xvfb prints (appended); otherwise /dev/null.
  explicit XDisplay(const std::filesystem::path& xvfb_log = {});
  ~XDisplay();
  XDisplay(const XDisplay&) = delete;
  XDisplay& operator=(const XDisplay&) = delete;

  /// True when this object started an Xvfb.
  bool started() const { return m_pid > 0; }
  /// The display in use, e.g. ":0" or ":90".
  const std::string& name() const { return m_name; }
  /// False once a started Xvfb has exited (true for a display that was already set).
  bool running();

 private:
  pid_t m_pid = -1;
  bool m_exited = false;  ///< the started Xvfb has exited and was reaped
  std::string m_name;
};

}  // namespace stiffsoft
