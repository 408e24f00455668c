#include <stiffsoft/scene/printable.hpp>

#include <cstdint>

namespace stiffsoft {

namespace {

/// Length in bytes of the valid UTF-8 sequence at text[i], and its code point; 0 when the bytes
/// there do not form one (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF).
std::size_t sequence_at(std::string_view text, std::size_t i, std::uint32_t& code) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  std::uint32_t lowest = 0;
  if (lead < 0x80) {
    code = lead;
    return 1;
  }
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
    code = lead & 0x1F;
    lowest = 0x80;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    code = lead & 0x0F;
    lowest = 0x800;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    code = lead & 0x07;
    lowest = 0x10000;
  } else {
    return 0;
  }
  if (i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  if (code < lowest || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  return length;
}

bool is_control(std::uint32_t code) { return code < 0x20 || code == 0x7F || (code >= 0x80 && code <= 0x9F); }

/// Calls visit(i, length, code) for each UTF-8 sequence of text in order: length 0 for a byte
/// that starts none (the scan then goes on at the next byte). Stops, returning false, at the
/// first visit that returns false; true when every visit did.
template <class Visit>
bool for_each_sequence(std::string_view text, Visit visit) {
  for (std::size_t i = 0; i < text.size();) {
    std::uint32_t code = 0;
    const std::size_t length = sequence_at(text, i, code);
    if (!visit(i, length, code)) return false;
    i += length == 0 ? 1 : length;
  }
  return true;
}

void append_escaped(std::string& out, unsigned char byte) {
  constexpr char kHex[] = "0123456789ABCDEF";
  out += "\\x";
  out += kHex[byte >> 4];
  out += kHex[byte & 0xF];
}

}  // namespace

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for_each_sequence(text, [&](std::size_t i, std::size_t length, std::uint32_t code) {
    if (length == 0) {
      append_escaped(out, static_cast<unsigned char>(text[i]));
    } else if (is_control(code)) {
      for (std::size_t k = 0; k < length; ++k) append_escaped(out, static_cast<unsigned char>(text[i + k]));
    } else {
      out.append(text.substr(i, length));
    }
    return true;
  });
  return out;
}

bool is_valid_utf8(std::string_view text) {
  return for_each_sequence(text, [](std::size_t, std::size_t length, std::uint32_t) { return length > 0; });
}

bool has_control_character(std::string_view text) {
  return !for_each_sequence(text, [](std::size_t, std::size_t length, std::uint32_t code) {
    return length == 0 || !is_control(code);
  });
}

bool is_blank(std::string_view text) {
  // An invalid byte is something, shown as \xNN.
  return for_each_sequence(text, [](std::size_t, std::size_t length, std::uint32_t code) {
    return length > 0 && (code == ' ' || (code >= 0x09 && code <= 0x0D) || code == 0xA0 || code == 0x1680 ||
                          (code >= 0x2000 && code <= 0x200B) || code == 0x2028 || code == 0x2029 ||
                          code == 0x202F || code == 0x205F || code == 0x3000 || code == 0xFEFF);
  });
}

}  // namespace stiffsoft
