#pragma once
/// @file Running a third-party library's work in a child process, so that its crash is an error
/// and not the end of the program (docs/robustness.md, "Fuzzing the loader": gmsh 4.8 dereferences
/// a null node in some malformed .msh files).

#include <functional>
#include <string>

namespace stiffsoft {

/// Runs `work` in a forked child process and waits for it. `work` must hand its result back
/// through the file system (the child's memory is gone when it returns).
/// - `work` returns: run_isolated() returns.
/// - `work` throws a std::exception: std::runtime_error with the same message.
/// - the child is killed by a signal (a segmentation fault inside the library, an abort):
///   std::runtime_error("<what>: <activity> crashed (signal N: NAME); the file is probably
///   malformed"); likewise a child that exits with another status (a sanitizer that caught the
///   crash): "crashed (exit status N)".
/// Standard streams are flushed before the fork, so nothing buffered is written twice.
/// @throws std::runtime_error also when the process cannot fork
void run_isolated(const std::string& what, const std::string& activity, const std::function<void()>& work);

}  // namespace stiffsoft
