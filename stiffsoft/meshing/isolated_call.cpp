#include <stiffsoft/meshing/isolated_call.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>

namespace stiffsoft {
namespace {

/// The child's exit status when `work` threw (its message is in the pipe); 0 when it returned.
constexpr int exception_status = 100;

/// Writes all of `text` to `fd` (the child's report), ignoring failures: the child exits next.
void write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

std::string read_all(int fd) {
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return text;
    text.append(buffer, static_cast<std::size_t>(n));
  }
}

/// The child's side: run `work`, report an exception's message through `fd`, exit without
/// running the parent's exit handlers or flushing its buffers again.
[[noreturn]] void child(int fd, const std::function<void()>& work) {
  int code = 0;
  try {
    work();
  } catch (const std::exception& e) {
    write_all(fd, e.what());
    code = exception_status;
  } catch (...) {
    write_all(fd, "unknown exception");
    code = exception_status;
  }
  std::fflush(nullptr);
  ::_exit(code);
}

}  // namespace

void run_isolated(const std::string& what, const std::string& activity, const std::function<void()>& work) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error(what + ": cannot run " + activity + ": pipe: " + std::strerror(errno));
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(what + ": cannot run " + activity + ": fork: " + std::strerror(error));
  }
  if (pid == 0) {
    ::close(fds[0]);
    child(fds[1], work);
  }
  ::close(fds[1]);
  const std::string report = read_all(fds[0]);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    throw std::runtime_error(what + ": " + activity + " crashed (signal " + std::to_string(signal) + ": " +
                             ::strsignal(signal) + "); the file is probably malformed");
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == exception_status) throw std::runtime_error(report);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)  // e.g. a sanitizer's report of the crash
    throw std::runtime_error(what + ": " + activity + " crashed (exit status " +
                             std::to_string(WEXITSTATUS(status)) + "); the file is probably malformed");
}

}  // namespace stiffsoft
