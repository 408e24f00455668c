#include <stiffsoft/libfem/format_number.hpp>

#include <charconv>
#include <cstdio>

namespace stiffsoft::fem {

std::string format_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string format_significant(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

}  // namespace stiffsoft::fem
