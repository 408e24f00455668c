#pragma once
/// @file `OUT/stats.csv`: one row per time step, columns chosen by the caller.

#include <filesystem>
#include <string>
#include <vector>

#include <stiffsoft/io/csv_rows.hpp>

namespace stiffsoft {

/// stats.csv: a header line (the column names, comma-separated), then one line per add_row().
/// Rows are kept in memory and the whole file is rewritten atomically (stiffsoft/io/atomic_file.hpp) on
/// flush() and at destruction, so the file on disk is always whole. Values are written in the
/// shortest form that reads back to the same double ("nan"/"inf" for non-finite values).
class StatsWriter {
 public:
  /// `file`: the .csv to (re)write; its folder must exist. `columns`: non-empty, names without
  /// ',', '"' or line breaks (throws std::invalid_argument otherwise). Nothing is written before flush() or destruction.
  StatsWriter(std::filesystem::path file, std::vector<std::string> columns);

  /// Rewrites the file unless nothing changed since the last successful flush() (so a writer
  /// that never flushed still leaves at least the header); a failure is reported on stderr,
  /// never thrown (destructors must not throw). Call flush() first to see errors.
  ~StatsWriter();

  StatsWriter(const StatsWriter&) = delete;             ///< one writer per file
  StatsWriter& operator=(const StatsWriter&) = delete;  ///< one writer per file

  /// Appends a row in memory; `values.size()` must equal the number of columns
  /// (throws std::invalid_argument otherwise).
  void add_row(const std::vector<double>& values);

  /// Rewrites the file with the header and every row so far. Throws std::runtime_error naming
  /// the file on I/O failure; the previous file content then stays intact.
  void flush();

  /// Continues a resumed run: takes `rows` (csv_rows_through_step of this file, read before
  /// the writer existed) as the rows so far.
  void reload(CsvRows rows);

  /// Number of rows added so far.
  std::size_t row_count() const;

 private:
  std::filesystem::path file_;        ///< the .csv
  std::vector<std::string> columns_;  ///< header names
  std::string rows_;                  ///< every row so far, already formatted, '\n'-terminated
  std::size_t row_count_ = 0;         ///< rows in rows_
  bool dirty_ = true;                 ///< file not yet written with the current rows
};

}  // namespace stiffsoft
