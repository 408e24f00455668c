#include <stiffsoft/io/stats_writer.hpp>

#include <charconv>
#include <stdexcept>

namespace stiffsoft {

StatsWriter::StatsWriter(std::filesystem::path file, std::vector<std::string> columns)
    : columns_(std::move(columns)), csv_(std::move(file), columns_) {
  if (columns_.empty()) {
    throw std::invalid_argument("stats file '" + csv_.file().string() + "': no columns given");
  }
  for (const std::string& column : columns_) {
    if (column.empty() || column.find_first_of(",\"\r\n") != std::string::npos) {
      throw std::invalid_argument("stats file '" + csv_.file().string() + "': column name '" + column +
                                  "' is empty or contains ',', '\"' or a line break");
    }
  }
}

void StatsWriter::add_row(const std::vector<double>& values) {
  if (values.size() != columns_.size()) {
    throw std::invalid_argument("stats file '" + csv_.file().string() + "': row has " +
                                std::to_string(values.size()) + " values, expected " +
                                std::to_string(columns_.size()));
  }
  // Formatting now keeps flush() a plain copy; to_chars gives the shortest round-trip text.
  char buffer[32];
  std::string& rows = csv_.rows();
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) rows += ',';
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), values[i]);
    rows.append(buffer, result.ptr);
  }
  rows += '\n';
  ++row_count_;
  csv_.added();
}

void StatsWriter::flush() { csv_.flush(); }

void StatsWriter::reload(const CsvEnd& end) { csv_.keep(end.length); }

std::size_t StatsWriter::row_count() const { return row_count_; }

}  // namespace stiffsoft
