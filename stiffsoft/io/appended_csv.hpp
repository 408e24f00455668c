#pragma once
/// @file A run's CSV file that grows at its end (stats.csv, bodies.csv, joints.csv): its rows
/// held in memory up to a bound, written whole at the first flush, appended after that, and
/// cut back to a resumed run's rows.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace stiffsoft {

/// The rows a CSV writer has not yet put on disk, and the file they go to. The first flush()
/// writes the header and the rows atomically (stiffsoft/io/atomic_file.hpp); later ones append
/// the rows in one write, so a long run's file is never rewritten (rewriting it at every frame
/// cost a run time quadratic in its length). Rows are held until flush(), destruction or the
/// bound, so a run with few frames (a large output.frame_dt) holds at most that much, not every
/// row since its last frame. A process killed during an append can leave a partial last line,
/// which a resumed run's reading (csv_rows.hpp) does not keep.
class AppendedCsv {
 public:
  /// Bytes of rows held before added() flushes them: 4 MiB, about 14 steps of bodies.csv on the
  /// 562-body pile `full` (290 kB a step). Held until the next frame, a run without frames grew
  /// by 0.6 MB a step there, each growth of the buffer touching fresh pages (15 µs a page fault
  /// on this project's machine; docs/benchmarks.md, "Memory of a long run").
  static constexpr std::size_t kPendingBytes = std::size_t(4) << 20;
  /// `file`: the .csv, in an existing folder; its header line names `columns` (csv_header_line).
  /// Nothing is written before flush(), destruction or `pending_bytes` of rows.
  AppendedCsv(std::filesystem::path file, const std::vector<std::string>& columns,
              std::size_t pending_bytes = kPendingBytes);
  /// Flushes unless nothing changed since the last flush (so a file never flushed still gets
  /// its header); a failure is reported on stderr, never thrown (destructors must not throw).
  ~AppendedCsv();
  AppendedCsv(const AppendedCsv&) = delete;             ///< one writer per file
  AppendedCsv& operator=(const AppendedCsv&) = delete;  ///< one writer per file

  /// The rows not yet on disk: a writer appends its '\n'-terminated lines here, then calls
  /// added().
  std::string& rows() { return m_rows; }
  /// After rows were appended: flushes once the rows held reach the bound (throwing as flush()).
  void added();
  /// Puts the rows held on disk: the header and them the first time (after keep(), the file cut
  /// to its kept bytes first), appended after that. Throws std::runtime_error naming the file
  /// on I/O failure; the rows then stay held.
  void flush();
  /// Continues a resumed run: the file's first `length` bytes (the header and the rows through
  /// the checkpoint's step, csv_end_through_step) stay; the next flush() cuts the file there.
  void keep(std::uintmax_t length);
  /// The file.
  const std::filesystem::path& file() const { return m_file; }

 private:
  std::filesystem::path m_file;  ///< the .csv
  std::string m_header;          ///< its first line, '\n' included
  std::size_t m_pending_bytes;   ///< rows held before added() flushes them
  std::string m_rows;            ///< rows not yet on disk
  bool m_dirty = true;           ///< rows (or the header) not yet on disk
  bool m_on_disk = false;        ///< the file holds the header and the rows flushed so far
  std::uintmax_t m_kept = 0;     ///< a resumed run's bytes to keep (keep()), cut at the next flush
};

}  // namespace stiffsoft
