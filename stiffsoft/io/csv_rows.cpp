#include <stiffsoft/io/csv_rows.hpp>

#include <charconv>
#include <fstream>
#include <iterator>

#include <stiffsoft/io/checkpoint.hpp>

namespace stiffsoft {

CsvRows csv_rows_through_step(const std::filesystem::path& file, const std::vector<std::string>& columns, int last_step) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ResumeError(file.string() + ": cannot be read, so the run cannot be resumed");
  const std::string bytes{std::istreambuf_iterator<char>(in), {}};
  std::string header;
  for (std::size_t i = 0; i < columns.size(); ++i) header += (i ? "," : "") + columns[i];
  header += '\n';
  if (bytes.compare(0, header.size(), header) != 0)
    throw ResumeError(file.string() + ": not the header this version writes, so the run cannot be resumed");
  CsvRows rows;
  for (std::size_t begin = header.size(); begin < bytes.size();) {
    const std::size_t end = bytes.find('\n', begin);
    if (end == std::string::npos) break;  // not a whole line
    int step = 0;
    const auto [ptr, error] = std::from_chars(bytes.data() + begin, bytes.data() + end, step);
    if (error != std::errc() || step > last_step) break;
    rows.text.append(bytes, begin, end + 1 - begin);
    ++rows.count;
    rows.last_step = step;
    begin = end + 1;
  }
  return rows;
}

}  // namespace stiffsoft
