#pragma once
/// @file ParaView output of a run: a .pvd time series of .vtm multiblocks, one .vtu per body.
///
/// Layout (design.md, "Output"):
/// - `OUT/<scene>.pvd`: one DataSet entry per frame written completely
///   (timestep = time, file = frames/<scene>_NNNNNN.vtm);
/// - `OUT/frames/<scene>_NNNNNN.vtm`: one block per body, block name = body name;
/// - `OUT/frames/<scene>_NNNNNN/<index>_<sanitized body name>.vtu`: a soft body's tetrahedra
///   (VTK_TETRA) followed by every body's surface triangles (VTK_TRIANGLE), point data
///   `velocity`, `displacement`, `contact_force`, `friction_force` (3 components), cell data
///   `von_mises` (Pa; a triangle carries its tetrahedron's value) when given, field data `time`
///   (double), `body`, `model` (strings); binary appended, zlib-compressed XML.
/// Every file is written atomically (stiffsoft/io/atomic_file.hpp); the .vtm after its .vtu files, the .pvd
/// after the .vtm, so the .pvd only ever lists complete frames.

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace stiffsoft {

/// One body in one frame: its surface, and for a soft body its tetrahedra too.
struct BodyFrame {
  std::string name;    ///< body name (block name in ParaView); any characters, sanitized for the file name
  std::string model;   ///< "affine", "fixed", "kinematic", "soft"
  Eigen::MatrixX3d x;  ///< world positions of the points (surface vertices, or all nodes of a soft body), |V|×3, m
  Eigen::MatrixX3i F;  ///< surface triangles (point indices into x, 0-based), |F|×3
  Eigen::MatrixX4i T;  ///< tetrahedra (point indices), |T|×4; empty for affine bodies
  Eigen::VectorXd von_mises;  ///< von Mises stress per cell (Pa), tetrahedra then triangles (|T| + |F|); or empty
  Eigen::MatrixX3d velocity;        ///< vertex velocities, |V|×3, m/s; or empty (written as zeros)
  Eigen::MatrixX3d displacement;    ///< x − rest position, |V|×3, m; or empty (written as zeros)
  Eigen::MatrixX3d contact_force;   ///< per-vertex contact force, |V|×3, N; or empty (zeros)
  Eigen::MatrixX3d friction_force;  ///< per-vertex friction force, |V|×3, N; or empty (zeros)
};

/// Writes the frames of one run into an output folder (creates it and frames/).
///
/// The constructor already writes an empty .pvd (so an unwritable folder fails early and the
/// .pvd of an older run in the same folder no longer lists its frames). Frame files of an older
/// run are not deleted; they are simply not listed.
class FrameWriter {
 public:
  /// Creates `out_dir` and `out_dir/frames` if needed and writes an empty `<scene_name>.pvd`.
  /// Throws std::runtime_error naming the folder/file when that fails, std::invalid_argument
  /// when `scene_name` is empty or contains a path separator.
  FrameWriter(std::filesystem::path out_dir, std::string scene_name);

  /// Writes frame number frame_count() at simulated time `time` (s) and appends it to the .pvd.
  /// Throws std::invalid_argument for inconsistent shapes (per-vertex arrays neither empty nor
  /// |V|×3, face indices outside [0, |V|)) and std::runtime_error naming the file on I/O failure;
  /// after a failure the .pvd still lists exactly the earlier, complete frames.
  void write(double time, const std::vector<BodyFrame>& bodies);

  /// Number of frames written so far.
  int frame_count() const;

  /// The .pvd's entries so far: (time in s, .vtm file relative to the output folder).
  const std::vector<std::pair<double, std::string>>& frames() const { return frames_; }

  /// Continues a resumed run whose .pvd listed `frames`: takes them as the frames so far and
  /// rewrites the .pvd with exactly them (later frame files are overwritten as they come again).
  void continue_from(std::vector<std::pair<double, std::string>> frames);

  /// Path of the .pvd: `out_dir/<scene_name>.pvd`.
  std::filesystem::path pvd_path() const;

 private:
  void write_pvd() const;

  std::filesystem::path out_dir_;                      ///< output folder OUT
  std::string scene_name_;                             ///< file stem of the .pvd and the frames
  std::vector<std::pair<double, std::string>> frames_; ///< (time, .vtm path relative to OUT) per frame
};

/// Writes (atomically) a ParaView .pvd collection listing `frames` (time in s, file relative to
/// the .pvd's folder), in order. Throws std::runtime_error naming the file on I/O failure.
void write_pvd_collection(const std::filesystem::path& pvd,
                          const std::vector<std::pair<double, std::string>>& frames);

/// The file-name-safe form of a body name: letters, digits, '-', '_' and '.' are kept, every
/// other byte becomes '_'; an empty name becomes "body". Used for `<index>_<name>.vtu`.
std::string sanitize_file_name(const std::string& name);

}  // namespace stiffsoft
