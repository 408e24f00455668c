#pragma once
/// @file Reading back the rows of a run's CSV files (stats.csv, bodies.csv, joints.csv) when a
/// run is resumed: every file starts each row with its step number, in increasing order.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace stiffsoft {

/// Rows of a CSV file, as written ('\n'-terminated lines, header excluded).
struct CsvRows {
  std::string text;        ///< the lines kept
  std::size_t count = 0;   ///< how many
  int last_step = -1;      ///< step of the last line kept; −1 when none
};

/// Where the rows of a CSV file through a step end.
struct CsvEnd {
  std::uintmax_t length = 0;  ///< bytes to keep: the header and the rows through the step
  int last_step = -1;         ///< step of the last row kept; −1 when none
};

/// The end of the rows of `file` whose step is at most `last_step`, for a file too long to
/// read back whole (a long run's bodies.csv): only the header and the lines after the last such
/// row are read, from the file's end. A partial last line is not kept. Throws ResumeError
/// (checkpoint.hpp) naming the file when it cannot be read, its header is not `columns` or a
/// line read does not start with a step number.
CsvEnd csv_end_through_step(const std::filesystem::path& file, const std::vector<std::string>& columns, int last_step);

/// The rows of `file` whose first field (the step) is at most `last_step`, found as
/// csv_end_through_step() finds their end (stats.csv, joints.csv: one row per step). Throws as it.
CsvRows csv_rows_through_step(const std::filesystem::path& file, const std::vector<std::string>& columns, int last_step);

}  // namespace stiffsoft
