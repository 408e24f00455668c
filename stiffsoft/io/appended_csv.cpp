#include <stiffsoft/io/appended_csv.hpp>

#include <fstream>
#include <iostream>
#include <stdexcept>
#include <system_error>

#include <stiffsoft/io/atomic_file.hpp>
#include <stiffsoft/io/csv_rows.hpp>

namespace stiffsoft {

AppendedCsv::AppendedCsv(std::filesystem::path file, const std::vector<std::string>& columns,
                         std::size_t pending_bytes)
    : m_file(std::move(file)), m_header(csv_header_line(columns)), m_pending_bytes(pending_bytes) {}

AppendedCsv::~AppendedCsv() {
  if (!m_dirty) return;
  try {
    flush();
  } catch (const std::exception& e) {
    std::cerr << "stiffsoft: " << e.what() << '\n';
  }
}

void AppendedCsv::added() {
  m_dirty = true;
  if (m_rows.size() >= m_pending_bytes) flush();
}

void AppendedCsv::flush() {
  if (!m_on_disk && m_kept > 0) {
    std::error_code error;
    std::filesystem::resize_file(m_file, m_kept, error);
    if (error)
      throw std::runtime_error("cannot cut " + m_file.string() + " to its resumed rows: " + error.message());
    m_on_disk = true;
  }
  if (!m_on_disk) {
    write_file_atomically(m_file, [&](std::ostream& out) { out << m_header << m_rows; });
    m_on_disk = true;
  } else if (!m_rows.empty()) {
    std::ofstream out(m_file, std::ios::binary | std::ios::app);
    out.write(m_rows.data(), std::streamsize(m_rows.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot append to " + m_file.string());
  }
  m_rows.clear();
  m_dirty = false;
}

void AppendedCsv::keep(std::uintmax_t length) {
  m_rows.clear();
  m_kept = length;
  m_on_disk = false;
  m_dirty = true;
}

}  // namespace stiffsoft
