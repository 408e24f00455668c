/// @file Numbers in messages: exact round trips and significant digits.

#include <gtest/gtest.h>

#include <stiffsoft/libfem/format_number.hpp>

namespace stiffsoft::fem {
namespace {

TEST(FormatNumber, ReadsBackExactly) {
  EXPECT_EQ(format_number(0.5), "0.5");
  EXPECT_EQ(std::stod(format_number(0.1 + 0.2)), 0.1 + 0.2);
}

TEST(FormatNumber, SignificantDigits) {
  EXPECT_EQ(format_significant(0.012345), "0.0123");
  EXPECT_EQ(format_significant(0.012345, 4), "0.01235");
  EXPECT_EQ(format_significant(1e8), "1e+08");
}

}  // namespace
}  // namespace stiffsoft::fem
