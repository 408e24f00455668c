#pragma once
/// @file ParaView output of a run's joints: a .pvd time series of .vtp PolyData files, one per
/// written frame, beside the bodies' series (frame_writer.hpp).
///
/// Layout:
/// - `OUT/<scene>_joints.pvd`: one DataSet entry per frame (timestep = time,
///   file = frames/<scene>_joints_NNNNNN.vtp);
/// - `OUT/frames/<scene>_joints_NNNNNN.vtp`: two points per joint (its anchor on body a, then
///   its point on body b; they coincide for ball, cone-twist and hinge joints), one line cell
///   per joint between them. Cell data: `joint` (index in the scene's `joints`), `kind`
///   (JointKind's index in the field data `kind_names`), `force` (3 components, the joint's
///   force on body a, N), `force_magnitude` (N), `gap` (smallest gap to the joint's limits, rad
///   or m; NaN where it has none). Point data: `joint`, `end` (0: body a, 1: body b), `force`
///   (the force on that end's body: +F at a, −F at b, N). Field data: `time`, `joint_names`,
///   `kind_names`. Binary appended, zlib-compressed XML.
/// Every file is written atomically (stiffsoft/io/atomic_file.hpp), the .vtp before the .pvd that lists it.

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace stiffsoft {

/// One joint in one frame.
struct JointFrameEntry {
  std::string name;                                  ///< the joint's name
  int kind = 0;                                      ///< JointKind as an integer
  Eigen::Vector3d x_a = Eigen::Vector3d::Zero();     ///< anchor on body a, world (m)
  Eigen::Vector3d x_b = Eigen::Vector3d::Zero();     ///< point on body b, world (m)
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< the joint's force on body a (N)
  double gap = 0;                                    ///< smallest gap to a limit (rad or m); NaN: no limit
};

/// Writes the joints' frames of one run (creates `out_dir/frames` if needed).
class JointFrameWriter {
 public:
  /// Writes an empty `<scene_name>_joints.pvd` in `out_dir`. Throws std::runtime_error naming
  /// the folder or file when that fails, std::invalid_argument for an empty scene name or one
  /// with a '/'.
  JointFrameWriter(std::filesystem::path out_dir, std::string scene_name);
  /// Writes frame number frame_count() at simulated time `time` (s) and lists it in the .pvd.
  /// Throws std::runtime_error naming the file on I/O failure.
  void write(double time, const std::vector<JointFrameEntry>& joints);
  /// Number of frames written so far.
  int frame_count() const { return int(m_frames.size()); }
  /// The .pvd's entries so far: (time in s, file relative to out_dir).
  const std::vector<std::pair<double, std::string>>& frames() const { return m_frames; }
  /// Continues a resumed run whose .pvd listed `frames`: takes them as the frames so far and
  /// rewrites the .pvd with exactly them.
  void continue_from(std::vector<std::pair<double, std::string>> frames);
  /// `out_dir/<scene_name>_joints.pvd`.
  std::filesystem::path pvd_path() const;

 private:
  std::filesystem::path m_out_dir;
  std::string m_stem;  // <scene>_joints
  std::vector<std::pair<double, std::string>> m_frames;
};

}  // namespace stiffsoft
