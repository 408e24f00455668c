#include <stiffsoft/io/appended_csv.hpp>

#include <fstream>
#include <stdexcept>
#include <system_error>

#include <stiffsoft/io/atomic_file.hpp>
#include <stiffsoft/io/csv_rows.hpp>

namespace stiffsoft {

AppendedCsv::AppendedCsv(std::filesystem::path file, const std::vector<std::string>& columns)
    : m_file(std::move(file)), m_header(csv_header_line(columns)) {}

void AppendedCsv::write(const std::string& rows) {
  if (!m_on_disk && m_kept > 0) {
    std::error_code error;
    std::filesystem::resize_file(m_file, m_kept, error);
    if (error)
      throw std::runtime_error("cannot cut " + m_file.string() + " to its resumed rows: " + error.message());
    m_on_disk = true;
  }
  if (!m_on_disk) {
    write_file_atomically(m_file, [&](std::ostream& out) { out << m_header << rows; });
    m_on_disk = true;
  } else if (!rows.empty()) {
    std::ofstream out(m_file, std::ios::binary | std::ios::app);
    out.write(rows.data(), std::streamsize(rows.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot append to " + m_file.string());
  }
}

void AppendedCsv::keep(std::uintmax_t length) {
  m_kept = length;
  m_on_disk = false;
}

}  // namespace stiffsoft
