#include <stiffsoft/io/csv_rows.hpp>

#include <algorithm>
#include <charconv>
#include <fstream>

#include <stiffsoft/io/checkpoint.hpp>

namespace stiffsoft {

namespace {

/// Bytes read at a time from a file's end.
constexpr std::uintmax_t kBlock = 1 << 20;

/// `file`, open for reading, after checking that it starts with `header`.
std::ifstream checked_file(const std::filesystem::path& file, const std::string& header) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ResumeError(file.string() + ": cannot be read, so the run cannot be resumed");
  std::string start(header.size(), '\0');
  in.read(start.data(), std::streamsize(start.size()));
  if (std::size_t(in.gcount()) != header.size() || start != header)
    throw ResumeError(file.string() + ": not the header this version writes, so the run cannot be resumed");
  return in;
}

/// The step a line starts with; false when it does not start with a number.
bool step_of(const char* begin, const char* end, int& step) {
  return std::from_chars(begin, end, step).ec == std::errc();
}

}  // namespace

std::string csv_header_line(const std::vector<std::string>& columns) {
  std::string header;
  for (std::size_t i = 0; i < columns.size(); ++i) header += (i ? "," : "") + columns[i];
  return header + '\n';
}

CsvEnd csv_end_through_step(const std::filesystem::path& file, const std::vector<std::string>& columns, int last_step) {
  const std::string header = csv_header_line(columns);
  std::ifstream in = checked_file(file, header);
  const std::uintmax_t first = header.size(), size = std::filesystem::file_size(file);
  // `text` holds the file's bytes [from, to): the lines not yet looked at, the last one cut
  // at `to`, which is a line's end ('\n' excluded) once the partial last line is dropped.
  std::string text;
  std::uintmax_t from = size, to = size;
  bool whole = false;  // text's last line ends at `to`
  while (true) {
    const std::size_t newline = text.rfind('\n');
    if (!whole) {  // drop what follows the last '\n' (a partial line, or nothing)
      if (newline != std::string::npos) {
        to = from + newline;
        text.resize(newline);
        whole = true;
        continue;
      }
    } else if (newline != std::string::npos || from == first) {
      // The last line is text's tail after that '\n' (or all of text at the header).
      const std::size_t begin = newline == std::string::npos ? 0 : newline + 1;
      int step = 0;
      if (!step_of(text.data() + begin, text.data() + text.size(), step))
        throw ResumeError(file.string() + ": a line that does not start with a step number (a damaged file, or a name " +
                          "with a line break), so the run cannot be resumed");
      if (step <= last_step) return {to + 1, step};
      to = from + begin - 1;  // the '\n' before it, or the header's
      text.resize(begin == 0 ? 0 : begin - 1);
      if (begin == 0) return {first, -1};
      continue;
    }
    if (from == first) return {first, -1};  // no whole line
    const std::uintmax_t block = std::min(kBlock, from - first);
    from -= block;
    std::string before(std::size_t(block), '\0');
    in.seekg(std::streamoff(from));
    in.read(before.data(), std::streamsize(block));
    if (std::uintmax_t(in.gcount()) != block) throw ResumeError(file.string() + ": cannot be read, so the run cannot be resumed");
    text.insert(0, before);
  }
}

}  // namespace stiffsoft
