#pragma once
/// @file `OUT/stats.csv`: one row per time step, columns chosen by the caller.

#include <filesystem>
#include <string>
#include <vector>

#include <stiffsoft/io/appended_csv.hpp>
#include <stiffsoft/io/csv_rows.hpp>

namespace stiffsoft {

/// stats.csv: a header line (the column names, comma-separated), then one line per add_row().
/// Rows are held and written as AppendedCsv holds and writes them (whole once, then appended;
/// at flush(), destruction or its bound). Values are written in the shortest form that reads
/// back to the same double ("nan"/"inf" for non-finite values).
class StatsWriter {
 public:
  /// `file`: the .csv to (re)write; its folder must exist. `columns`: non-empty, names without
  /// ',', '"' or line breaks (throws std::invalid_argument otherwise). Nothing is written
  /// before flush(), destruction or AppendedCsv's bound.
  StatsWriter(std::filesystem::path file, std::vector<std::string> columns);

  StatsWriter(const StatsWriter&) = delete;             ///< one writer per file
  StatsWriter& operator=(const StatsWriter&) = delete;  ///< one writer per file

  /// Appends a row in memory; `values.size()` must equal the number of columns
  /// (throws std::invalid_argument otherwise). Flushes once the rows held reach the bound.
  void add_row(const std::vector<double>& values);

  /// Puts the rows held on disk (AppendedCsv::flush). Throws std::runtime_error naming the file
  /// on I/O failure; the rows then stay held.
  void flush();

  /// Continues a resumed run: the file's first `end.length` bytes (csv_end_through_step of this
  /// file, read before the writer existed) are its header and the rows so far; the next flush
  /// cuts the file there and appends.
  void reload(const CsvEnd& end);

  /// Number of rows add_row() added (a resumed run's earlier rows not counted).
  std::size_t row_count() const;

 private:
  std::vector<std::string> columns_;  ///< header names
  AppendedCsv csv_;                   ///< the rows held and the .csv on disk
  std::size_t row_count_ = 0;         ///< rows add_row() added
};

}  // namespace stiffsoft
