#pragma once
/// @file Reads back one joints frame written by JointFrameWriter (stiffsoft/io/joint_frame_writer.hpp),
/// through VTK's XML PolyData reader: for tests and tools.

#include <filesystem>
#include <vector>

#include <stiffsoft/io/joint_frame_writer.hpp>

namespace stiffsoft {

/// One joints frame as read back.
struct JointFrameRead {
  double time = 0;                      ///< field data `time` (s)
  std::vector<JointFrameEntry> joints;  ///< one per line cell, in order
};

/// Reads `frames/<scene>_joints_NNNNNN.vtp`. Throws std::runtime_error naming the file when
/// it cannot be read or lacks the arrays JointFrameWriter writes.
JointFrameRead read_joint_frame(const std::filesystem::path& vtp);

}  // namespace stiffsoft
