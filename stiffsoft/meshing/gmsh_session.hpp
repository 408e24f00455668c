#pragma once
/// @file One gmsh session at a time: gmsh is a process-wide singleton.

#include <cstddef>
#include <functional>
#include <string>

namespace stiffsoft {

/// Runs `body` inside one gmsh session: takes the process-wide gmsh lock (one session at a time,
/// across threads), calls gmsh::initialize (no configuration files read), sets General.Terminal to
/// `verbose` (nothing is printed otherwise) and General.NumThreads = 1 (reproducible meshes),
/// starts gmsh's logger, runs `body`, and always calls gmsh::finalize, so every session starts from
/// gmsh's defaults.
/// A gmsh error (gmsh 4.8 throws a std::string) becomes std::runtime_error("<what>: gmsh: <message>");
/// every other exception passes through unchanged.
/// @throws std::logic_error when called from inside another session's `body` (not reentrant)
void run_gmsh(const std::string& what, bool verbose, const std::function<void()>& body);

/// gmsh's logged error lines of the running session, joined by "; " (empty when there are none).
/// Call only from inside a run_gmsh body.
std::string gmsh_logged_errors();

/// How many gmsh sessions run_gmsh has started in this process (lets a test show that a cache hit
/// never starts gmsh).
std::size_t gmsh_session_count();

}  // namespace stiffsoft
