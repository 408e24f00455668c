#pragma once
/// @file A run's CSV file that grows at its end (stats.csv, bodies.csv, joints.csv): written
/// whole at its first flush, appended after that, and cut back to a resumed run's rows.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace stiffsoft {

/// The file on disk behind a CSV writer: the first write() puts the header and the rows given
/// atomically (stiffsoft/io/atomic_file.hpp); later ones append their rows in one write, so a
/// long run's file is never rewritten (rewriting it at every frame cost a run time quadratic in
/// its length). A process killed during an append can leave a partial last line, which a
/// resumed run's reading (csv_rows.hpp) does not keep.
class AppendedCsv {
 public:
  /// `file`: the .csv, in an existing folder; its header line names `columns` (csv_header_line).
  AppendedCsv(std::filesystem::path file, const std::vector<std::string>& columns);
  /// Puts `rows` ('\n'-terminated lines) on disk: the header and the rows the first time (after
  /// keep(), the file cut to its kept bytes first), appended after that. Throws
  /// std::runtime_error naming the file on I/O failure.
  void write(const std::string& rows);
  /// Continues a resumed run: the file's first `length` bytes (the header and the rows through
  /// the checkpoint's step, csv_end_through_step) stay; the next write() cuts the file there.
  void keep(std::uintmax_t length);
  /// The file.
  const std::filesystem::path& file() const { return m_file; }

 private:
  std::filesystem::path m_file;  ///< the .csv
  std::string m_header;          ///< its first line, '\n' included
  bool m_on_disk = false;        ///< the file holds the header and the rows written so far
  std::uintmax_t m_kept = 0;     ///< a resumed run's bytes to keep (keep()), cut at the next write
};

}  // namespace stiffsoft
