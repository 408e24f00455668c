#pragma once
/// @file The benchmark's CSV: `#` comment lines with the machine, then one row per run.

#include <ostream>

#include "peers/machine.hpp"
#include "peers/runner.hpp"

namespace stiffsoft::peers {

/// Writes the machine as comment lines and the header row.
void write_csv_header(std::ostream& out, const Machine& machine, int threads);

/// Writes one run as a row (strings quoted, lengths in metres, times in ms or s as named).
void write_csv_row(std::ostream& out, const RunResult& r);

}  // namespace stiffsoft::peers
