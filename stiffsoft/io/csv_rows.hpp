#pragma once
/// @file Reading back the rows of a run's CSV files (stats.csv, bodies.csv, joints.csv) when a
/// run is resumed: every file starts each row with its step number.

#include <cstddef>
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

/// The rows of `file` whose first field (the step) is at most `last_step`. Throws ResumeError
/// (checkpoint.hpp) naming the file when it cannot be read or its header is not `columns`.
CsvRows csv_rows_through_step(const std::filesystem::path& file, const std::vector<std::string>& columns, int last_step);

}  // namespace stiffsoft
