#include <stiffsoft/libfem/format_number.hpp>

#include <charconv>

namespace stiffsoft::fem {

std::string format_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace stiffsoft::fem
