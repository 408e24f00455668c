#pragma once
/// @file `OUT/bodies.csv`: every body's state after every step (and at t = 0), for studies
/// and plots that need a body's position, orientation or velocity at a time.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <stiffsoft/coupling/solver/simulation.hpp>
#include <stiffsoft/io/appended_csv.hpp>
#include <stiffsoft/io/csv_rows.hpp>

namespace stiffsoft {

/// bodies.csv: header `step,time,body,px,py,pz,vx,vy,vz,wx,wy,wz,A00,…,A22,kinetic_energy,
/// fcx,fcy,fcz,ffx,ffy,ffz`, then one line per body per add_state() call.
/// - Affine (and fixed, kinematic) bodies: p is the centre of mass (m), v its velocity (m/s),
///   w the world angular velocity of the rigid part (rad/s), A the affine matrix (row-major,
///   A_ij = row i, column j), kinetic energy ½ q̇ᵀ M q̇ (J).
/// - Soft bodies: p and v are the mass-weighted mean of the nodes' positions and velocities,
///   w and A are written as nan, kinetic energy Σ ½ mᵢ |vᵢ|² (J).
/// - fc, ff: the sum of the contact (barrier) and friction forces on the body's surface
///   vertices (N).
/// Rows are kept in memory until flush() (and destruction), or until they reach the writer's
/// bound (kBodyRowsPendingBytes), when add_state() flushes them itself: a run with few frames
/// (a large output.frame_dt) holds at most that much, not every row since its last frame. The
/// file is written whole once and then appended (AppendedCsv); a resumed run (reload()) cuts
/// it after the checkpoint's rows at its first flush, so that resuming reads and holds none of
/// the rows it keeps.
class BodyStateWriter {
 public:
  /// Bytes of rows held in memory before add_state() appends them to the file: 4 MiB, about 14
  /// steps of the 562-body pile `full` (290 kB a step). Held until the next frame, a run without
  /// frames grew by 0.6 MB a step there, each growth of the buffer touching fresh pages (15 µs a
  /// page fault on this project's machine; docs/benchmarks.md, "Memory of a long run").
  static constexpr std::size_t kBodyRowsPendingBytes = std::size_t(4) << 20;
  /// `file`: the .csv to (re)write; its folder must exist. Nothing is written before flush() or
  /// before the rows held reach `pending_bytes`.
  explicit BodyStateWriter(std::filesystem::path file, std::size_t pending_bytes = kBodyRowsPendingBytes);
  /// Flushes unless nothing changed; errors go to stderr (destructors must not throw).
  ~BodyStateWriter();
  BodyStateWriter(const BodyStateWriter&) = delete;             ///< one writer per file
  BodyStateWriter& operator=(const BodyStateWriter&) = delete;  ///< one writer per file

  /// Appends one row per body of `sim` for step number `step` (0: the initial state); flushes
  /// when the rows held reach the bound (throwing as flush() does).
  void add_state(int step, const Simulation& sim);
  /// Puts every row so far on disk (header and rows the first time, then appending); throws
  /// std::runtime_error naming the file on I/O failure.
  void flush();
  /// Continues a resumed run: the file's first `end.length` bytes (csv_end_through_step of
  /// this file, read before the writer existed) are its header and the rows so far; the next
  /// flush cuts the file there and appends.
  void reload(const CsvEnd& end);

 private:
  AppendedCsv csv_;             ///< the .csv on disk
  std::size_t pending_bytes_;   ///< rows held before add_state() flushes them
  std::string rows_;            ///< rows not yet on disk, '\n'-terminated
  bool dirty_ = true;           ///< rows (or the header) not yet on disk
};

/// The column names of bodies.csv, in order.
const std::vector<std::string>& body_state_columns();

}  // namespace stiffsoft
