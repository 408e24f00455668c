#pragma once
/// @file Text from a scene file made safe to print in a message: a name or key may hold bytes
/// that are not valid UTF-8, or control characters, which would garble a terminal or a log.

#include <string>
#include <string_view>

namespace stiffsoft {

/// `text` with every byte that is not part of a printable character written as `\xNN` (two
/// upper-case hex digits): bytes that do not form valid UTF-8 (a stray 0xFF, a truncated or
/// overlong sequence, a surrogate), C0 control characters (U+0000–U+001F, tab and newline
/// included), DEL (U+007F) and C1 control characters (U+0080–U+009F, each of its two bytes).
/// Valid printable UTF-8 (é, d̂, ≥, −) passes unchanged; `\` itself is not escaped.
std::string printable(std::string_view text);

/// True when `text` is valid UTF-8 (no stray, truncated, overlong or surrogate sequences).
bool is_valid_utf8(std::string_view text);

/// True when `text` holds a C0 or C1 control character or DEL (see printable()).
bool has_control_character(std::string_view text);

/// True when `text` shows nothing: empty, or only white space, ASCII (space, tab, newline, ...)
/// or Unicode (no-break space U+00A0, U+1680, U+2000–U+200B, U+2028, U+2029, U+202F, U+205F,
/// U+3000, U+FEFF).
bool is_blank(std::string_view text);

}  // namespace stiffsoft
