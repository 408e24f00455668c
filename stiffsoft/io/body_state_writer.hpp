#pragma once
/// @file `OUT/bodies.csv`: every body's state after every step (and at t = 0), for studies
/// and plots that need a body's position, orientation or velocity at a time.

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <stiffsoft/coupling/solver/simulation.hpp>
#include <stiffsoft/io/appended_csv.hpp>
#include <stiffsoft/io/csv_rows.hpp>

namespace stiffsoft {

/// One body's row of bodies.csv without its step, time and name (the columns below).
struct BodyState {
  Eigen::Vector3d p;          ///< centre of mass (affine) or mass-weighted mean of the nodes (soft), m
  Eigen::Vector3d v;          ///< its velocity, m/s
  Eigen::Vector3d w;          ///< world angular velocity of the rigid part, rad/s; nan for a soft body
  Eigen::Matrix3d A;          ///< the affine matrix; nan for a soft body
  double kinetic_energy = 0;  ///< J
  Eigen::Vector3d fc;         ///< sum of the contact (barrier) forces on the body's surface, N
  Eigen::Vector3d ff;         ///< sum of the friction forces on the body's surface, N
};

/// Every body's state in `sim`, in the model's order: what add_state() writes, taken apart
/// from its formatting so that a writer on another thread can format it (io/recorder.hpp).
std::vector<BodyState> body_states(const Simulation& sim);

/// The bodies' names, in the model's order: bodies.csv's `body` column.
std::vector<std::string> body_names(const Model& model);

/// bodies.csv: header `step,time,body,px,py,pz,vx,vy,vz,wx,wy,wz,A00,…,A22,kinetic_energy,
/// fcx,fcy,fcz,ffx,ffy,ffz`, then one line per body per add_state() call.
/// - Affine (and fixed, kinematic) bodies: p is the centre of mass (m), v its velocity (m/s),
///   w the world angular velocity of the rigid part (rad/s), A the affine matrix (row-major,
///   A_ij = row i, column j), kinetic energy ½ q̇ᵀ M q̇ (J).
/// - Soft bodies: p and v are the mass-weighted mean of the nodes' positions and velocities,
///   w and A are written as nan, kinetic energy Σ ½ mᵢ |vᵢ|² (J).
/// - fc, ff: the sum of the contact (barrier) and friction forces on the body's surface
///   vertices (N).
/// Rows are held and written as AppendedCsv holds and writes them (whole once, then appended;
/// at flush(), destruction or its bound); a resumed run (reload()) cuts the file after the
/// checkpoint's rows at its first flush, so that resuming reads and holds none of the rows it
/// keeps.
class BodyStateWriter {
 public:
  /// `file`: the .csv to (re)write; its folder must exist. Nothing is written before flush(),
  /// destruction or `pending_bytes` of rows.
  explicit BodyStateWriter(std::filesystem::path file,
                           std::size_t pending_bytes = AppendedCsv::kPendingBytes);
  BodyStateWriter(const BodyStateWriter&) = delete;             ///< one writer per file
  BodyStateWriter& operator=(const BodyStateWriter&) = delete;  ///< one writer per file

  /// Appends one row per body of `sim` for step number `step` (0: the initial state); flushes
  /// when the rows held reach the bound (throwing as flush() does).
  void add_state(int step, const Simulation& sim);
  /// Appends one row per body, `names[b]` and `states[b]` (body_states()) at step number `step`
  /// and simulated time `time` (s); flushes as add_state() does. The sizes must match
  /// (std::invalid_argument otherwise).
  void add_states(int step, double time, const std::vector<std::string>& names,
                  const std::vector<BodyState>& states);
  /// Puts every row so far on disk (header and rows the first time, then appending); throws
  /// std::runtime_error naming the file on I/O failure.
  void flush();
  /// Continues a resumed run: the file's first `end.length` bytes (csv_end_through_step of
  /// this file, read before the writer existed) are its header and the rows so far; the next
  /// flush cuts the file there and appends.
  void reload(const CsvEnd& end);

 private:
  AppendedCsv csv_;  ///< the rows held and the .csv on disk
};

/// The column names of bodies.csv, in order.
const std::vector<std::string>& body_state_columns();

}  // namespace stiffsoft
