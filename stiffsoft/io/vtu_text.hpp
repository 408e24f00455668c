#pragma once
/// @file A VTK XML unstructured grid (.vtu) serialised directly, in the layout
/// vtkXMLUnstructuredGridWriter writes with appended raw data, zlib compression and UInt64
/// headers, so that VTK and ParaView read it as theirs. Going through VTK's writer cost most
/// of a run's output time on scenes of many small bodies (a pipeline, array ranges and a new
/// zlib stream for every array of every body; docs/benchmarks.md, "Writing frames").
///
/// Arrays are compressed in blocks of 32 KiB, each block one zlib stream: the appended data
/// of an array is its header (block count, block size, size of a partial last block, then
/// each block's compressed size, all UInt64) followed by the compressed blocks. A block is
/// deflated when at least a quarter of its bytes are zero (cells, mostly zero forces) and
/// stored in its zlib stream otherwise (the moving bodies' positions and velocities, which
/// deflate shrinks by 0–20 % at 20–40 times the time).

#include <cstdint>
#include <string>

namespace stiffsoft {

/// One .vtu file's text, built array by array.
class VtuText {
 public:
  /// A grid of `points` points and `cells` cells.
  VtuText(std::int64_t points, std::int64_t cells);
  /// Field data: one double.
  void add_field(const std::string& name, double value);
  /// Field data: one string.
  void add_field(const std::string& name, const std::string& value);
  /// The points, `xyz` holding x, y, z of each point in turn.
  void set_points(const double* xyz);
  /// The cells: `ends[c]` is one past cell c's last entry in `connectivity` (VTK's XML
  /// offsets), `types[c]` its VTK cell type.
  void set_cells(const std::int64_t* connectivity, const std::int64_t* ends, const std::uint8_t* types);
  /// Point data with three components per point.
  void add_point_vectors(const std::string& name, const double* xyz);
  /// Cell data with one component per cell.
  void add_cell_scalars(const std::string& name, const double* values);
  /// The whole file.
  std::string str() const;

 private:
  /// Appends `bytes` bytes compressed and returns the offset they start at.
  std::size_t append(const void* data, std::size_t bytes);

  std::int64_t m_points, m_cells;
  std::string m_field, m_point_data, m_cell_data, m_points_tag, m_cells_tags;
  std::string m_appended;
};

}  // namespace stiffsoft
