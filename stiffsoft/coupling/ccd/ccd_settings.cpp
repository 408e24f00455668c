#include <stiffsoft/coupling/ccd/ccd_settings.hpp>

#include <stdexcept>

namespace stiffsoft::ccd {

void throw_invalid(const char* field_and_requirement, const std::string& value) {
  throw std::invalid_argument(std::string("CcdSettings.") + field_and_requirement + ", got " + value);
}

}  // namespace stiffsoft::ccd
