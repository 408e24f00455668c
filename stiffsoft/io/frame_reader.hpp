#pragma once
/// @file Reading back the output of FrameWriter (stiffsoft/io/frame_writer.hpp), for `stiffsoft check`.

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace stiffsoft {

/// One frame listed in a .pvd time series.
struct PvdEntry {
  double time;                 ///< simulated time of the frame (s), the `timestep` attribute
  std::filesystem::path file;  ///< the frame's .vtm, resolved against the .pvd's folder
};

/// The frames listed in a .pvd (`<DataSet timestep=".." file=".."/>` entries, in file order).
/// Throws std::runtime_error naming the file when it is missing, unreadable, not a
/// `VTKFile type="Collection"`, or an entry lacks a numeric `timestep` or a `file`.
std::vector<PvdEntry> read_pvd(const std::filesystem::path& pvd);

/// One block's surface as read back from a frame.
struct NamedSurface {
  std::string name;    ///< block name (the body's name)
  Eigen::MatrixX3d x;  ///< all points of the block, |V|×3, m
  Eigen::MatrixX3i F;  ///< the block's triangle cells, |F|×3, indices into x
};

/// The surfaces of every block of a .vtm written by FrameWriter, in block order.
/// Only cells of type VTK_TRIANGLE are returned in F; other cells (e.g. the tets of later soft
/// bodies) are skipped, while x keeps every point so the indices stay valid.
/// Leaves are read from the `<DataSet name=".." file=".."/>` entries (nested `<Block>`
/// elements are flattened; the file is resolved against the .vtm's folder).
/// Throws std::runtime_error naming the file when the .vtm or a .vtu is missing or malformed.
std::vector<NamedSurface> read_frame(const std::filesystem::path& vtm);

/// A 3-component point-data array of a .vtu (e.g. "velocity"), |V|×3.
/// Throws std::runtime_error naming the file when it cannot be read or has no 3-component
/// point array called `array_name`.
Eigen::MatrixX3d read_point_vectors(const std::filesystem::path& vtu, const std::string& array_name);

}  // namespace stiffsoft
