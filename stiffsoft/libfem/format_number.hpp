#pragma once
/// @file Numbers in error messages, written so they read back exactly.

#include <string>

namespace stiffsoft::fem {

/// The shortest decimal text that reads back as `value` (e.g. "0.5", "1e-13").
std::string format_number(double value);

/// `value` to `digits` significant digits, for measured numbers in messages (e.g. "0.0123", "1e+08").
std::string format_significant(double value, int digits = 3);

}  // namespace stiffsoft::fem
