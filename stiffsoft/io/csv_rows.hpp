#pragma once
/// @file Reading back the rows of a run's CSV files (stats.csv, bodies.csv, joints.csv) when a
/// run is resumed: every file starts each row with its step number, in increasing order.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace stiffsoft {

/// The header line a writer of `columns` puts first: the names joined by ',', then '\n'.
std::string csv_header_line(const std::vector<std::string>& columns);

/// Where the rows of a CSV file through a step end.
struct CsvEnd {
  std::uintmax_t length = 0;  ///< bytes to keep: the header and the rows through the step
  int last_step = -1;         ///< step of the last row kept; −1 when none
};

/// The end of the rows of `file` whose step is at most `last_step`, where a resumed run cuts
/// the file (AppendedCsv::keep): only the header and the lines after the last such row are
/// read, from the file's end, so a long run's file is not read back whole. A partial last line
/// is not kept. Throws ResumeError (checkpoint.hpp) naming the file when it cannot be read, its
/// header is not `columns` or a line read does not start with a step number.
CsvEnd csv_end_through_step(const std::filesystem::path& file, const std::vector<std::string>& columns, int last_step);

}  // namespace stiffsoft
