#pragma once
/// @file The machine the benchmark ran on, recorded with its results.

#include <string>

namespace stiffsoft::peers {

/// Cores, processor and time of a run.
struct Machine {
  unsigned cores = 0;     ///< std::thread::hardware_concurrency()
  std::string cpu;        ///< "model name" of /proc/cpuinfo ("unknown" when absent)
  std::string date;       ///< local date and time, ISO 8601
};

/// This machine, now.
Machine this_machine();

/// The 1-minute load average of /proc/loadavg, or −1 when unreadable.
double load_average();

}  // namespace stiffsoft::peers
