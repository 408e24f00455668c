#pragma once
/// @file `OUT/bodies.csv`: every body's state after every step (and at t = 0), for studies
/// and plots that need a body's position, orientation or velocity at a time.

#include <filesystem>
#include <string>
#include <vector>

#include <stiffsoft/coupling/solver/simulation.hpp>

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
/// Rows are kept in memory; the file is rewritten atomically (stiffsoft/io/atomic_file.hpp) on flush()
/// and at destruction, so it is always whole.
class BodyStateWriter {
 public:
  /// `file`: the .csv to (re)write; its folder must exist. Nothing is written before flush().
  explicit BodyStateWriter(std::filesystem::path file);
  /// Flushes unless nothing changed; errors go to stderr (destructors must not throw).
  ~BodyStateWriter();
  BodyStateWriter(const BodyStateWriter&) = delete;             ///< one writer per file
  BodyStateWriter& operator=(const BodyStateWriter&) = delete;  ///< one writer per file

  /// Appends one row per body of `sim` for step number `step` (0: the initial state).
  void add_state(int step, const Simulation& sim);
  /// Rewrites the file with the header and every row so far; throws std::runtime_error
  /// naming the file on I/O failure.
  void flush();
  /// Bytes of rows held in memory (callers flush large files less often).
  std::size_t size() const { return rows_.size(); }

 private:
  std::filesystem::path file_;  ///< the .csv
  std::string rows_;            ///< every row so far, '\n'-terminated
  bool dirty_ = true;           ///< rows not yet on disk
};

/// The column names of bodies.csv, in order.
const std::vector<std::string>& body_state_columns();

}  // namespace stiffsoft
