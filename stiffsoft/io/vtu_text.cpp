#include <stiffsoft/io/vtu_text.hpp>

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace stiffsoft {

namespace {

constexpr std::size_t kBlockSize = 32768;  // VTK's default block size

/// One deflate stream per thread and kind, reset between blocks: initialising a stream allocates
/// and clears about 256 KiB, which for small arrays cost more than compressing them.
class Deflater {
 public:
  /// zlib's `level` (0 stores), window of 2^`window_bits` bytes, hash table of 2^(`mem_level` + 8)
  /// bytes, cleared by every reset.
  Deflater(int level, int window_bits, int mem_level) {
    if (deflateInit2(&m_stream, level, Z_DEFLATED, window_bits, mem_level, Z_DEFAULT_STRATEGY) != Z_OK)
      throw std::runtime_error("zlib: deflateInit2 failed");
  }
  ~Deflater() { deflateEnd(&m_stream); }
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;

  /// Appends the zlib stream of `bytes` bytes at `data` to `out`; returns its size.
  std::size_t compress(const unsigned char* data, std::size_t bytes, std::string& out) {
    if (deflateReset(&m_stream) != Z_OK) throw std::runtime_error("zlib: deflateReset failed");
    const std::size_t start = out.size();
    out.resize(start + deflateBound(&m_stream, uLong(bytes)));
    m_stream.next_in = const_cast<unsigned char*>(data);
    m_stream.avail_in = uInt(bytes);
    m_stream.next_out = reinterpret_cast<unsigned char*>(out.data() + start);
    m_stream.avail_out = uInt(out.size() - start);
    if (deflate(&m_stream, Z_FINISH) != Z_STREAM_END) throw std::runtime_error("zlib: deflate did not finish");
    const std::size_t written = out.size() - start - m_stream.avail_out;
    out.resize(start + written);
    return written;
  }

 private:
  z_stream m_stream{};
};

/// The level-1 deflate stream of this thread for a block of `bytes` bytes: a window of
/// 2^w ≥ bytes (9 ≤ w ≤ 15) and a hash table of 2^w entries (mem_level w − 7), no larger than
/// the block needs. Every reset clears the table: at zlib's default (w = 15, 64 KiB) that was
/// two thirds of writing a pile's frame, whose arrays are a few hundred bytes each.
Deflater& deflater_for(std::size_t bytes) {
  thread_local std::array<std::unique_ptr<Deflater>, 7> by_window;
  int w = 9;
  while (w < MAX_WBITS && (std::size_t(1) << w) < bytes) ++w;
  std::unique_ptr<Deflater>& d = by_window[std::size_t(w - 9)];
  if (!d) d = std::make_unique<Deflater>(Z_BEST_SPEED, w, w - 7);
  return *d;
}

/// Whether deflate is worth its time on a block: at least a quarter of its bytes are zero. The
/// arrays that compress well are integers (the cells) and mostly zero forces; the positions
/// and velocities of moving bodies shrink by 0–20 % at 20–40 times the time of storing them
/// (docs/benchmarks.md, "Writing frames").
bool worth_deflating(const unsigned char* data, std::size_t bytes) {
  return 4 * std::size_t(std::count(data, data + bytes, 0)) >= bytes;
}

void append_uint64(std::string& out, std::uint64_t v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); }

/// The XML element of an array whose data is appended at `offset`.
std::string array_tag(const char* element, const char* type, const std::string& name, const std::string& extra,
                      std::size_t offset) {
  return std::string("<") + element + " type=\"" + type + "\" Name=\"" + name + "\"" + extra +
         " format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
}

}  // namespace

VtuText::VtuText(std::int64_t points, std::int64_t cells) : m_points(points), m_cells(cells) {}

std::size_t VtuText::append(const void* data, std::size_t bytes) {
  thread_local Deflater store(Z_NO_COMPRESSION, 9, 1);
  const std::size_t offset = m_appended.size();
  const std::size_t blocks = (bytes + kBlockSize - 1) / kBlockSize;
  append_uint64(m_appended, blocks);
  append_uint64(m_appended, kBlockSize);
  append_uint64(m_appended, bytes % kBlockSize);
  const std::size_t sizes_at = m_appended.size();
  for (std::size_t b = 0; b < blocks; ++b) append_uint64(m_appended, 0);
  const auto* begin = static_cast<const unsigned char*>(data);
  for (std::size_t b = 0; b < blocks; ++b) {
    const unsigned char* block = begin + b * kBlockSize;
    const std::size_t block_bytes = std::min(kBlockSize, bytes - b * kBlockSize);
    Deflater& deflater = worth_deflating(block, block_bytes) ? deflater_for(block_bytes) : store;
    const std::uint64_t size = deflater.compress(block, block_bytes, m_appended);
    std::memcpy(m_appended.data() + sizes_at + b * sizeof size, &size, sizeof size);
  }
  return offset;
}

void VtuText::add_field(const std::string& name, double value) {
  m_field += "      " + array_tag("DataArray", "Float64", name, " NumberOfTuples=\"1\"", append(&value, sizeof value));
}

void VtuText::add_field(const std::string& name, const std::string& value) {
  // VTK stores a string array as its strings, each followed by a zero byte.
  m_field += "      " + array_tag("Array", "String", name, " NumberOfTuples=\"1\"", append(value.c_str(), value.size() + 1));
}

void VtuText::set_points(const double* xyz) {
  m_points_tag = "        " + array_tag("DataArray", "Float64", "Points", " NumberOfComponents=\"3\"",
                                        append(xyz, sizeof(double) * 3 * std::size_t(m_points)));
}

void VtuText::set_cells(const std::int64_t* connectivity, const std::int64_t* ends, const std::uint8_t* types) {
  const std::size_t entries = m_cells ? std::size_t(ends[m_cells - 1]) : 0;
  m_cells_tags = "        " + array_tag("DataArray", "Int64", "connectivity", "", append(connectivity, sizeof(std::int64_t) * entries)) +
                 "        " + array_tag("DataArray", "Int64", "offsets", "", append(ends, sizeof(std::int64_t) * std::size_t(m_cells))) +
                 "        " + array_tag("DataArray", "UInt8", "types", "", append(types, std::size_t(m_cells)));
}

void VtuText::add_point_vectors(const std::string& name, const double* xyz) {
  m_point_data += "        " + array_tag("DataArray", "Float64", name, " NumberOfComponents=\"3\"",
                                         append(xyz, sizeof(double) * 3 * std::size_t(m_points)));
}

void VtuText::add_cell_scalars(const std::string& name, const double* values) {
  m_cell_data += "        " + array_tag("DataArray", "Float64", name, "", append(values, sizeof(double) * std::size_t(m_cells)));
}

std::string VtuText::str() const {
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\" "
      "compressor=\"vtkZLibDataCompressor\">\n"
      "  <UnstructuredGrid>\n"
      "    <FieldData>\n" +
      m_field +
      "    </FieldData>\n"
      "    <Piece NumberOfPoints=\"" + std::to_string(m_points) + "\" NumberOfCells=\"" + std::to_string(m_cells) + "\">\n"
      "      <PointData>\n" + m_point_data + "      </PointData>\n"
      "      <CellData>\n" + m_cell_data + "      </CellData>\n"
      "      <Points>\n" + m_points_tag + "      </Points>\n"
      "      <Cells>\n" + m_cells_tags + "      </Cells>\n"
      "    </Piece>\n"
      "  </UnstructuredGrid>\n"
      "  <AppendedData encoding=\"raw\">\n   _";
  out.reserve(out.size() + m_appended.size() + 32);
  out += m_appended;
  out += "\n  </AppendedData>\n</VTKFile>\n";
  return out;
}

}  // namespace stiffsoft
