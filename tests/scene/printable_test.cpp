#include <gtest/gtest.h>

#include <string>

#include <stiffsoft/scene/printable.hpp>

namespace stiffsoft {
namespace {

TEST(Printable, ValidPrintableUtf8PassesUnchanged) {
  EXPECT_EQ(printable("crate_1 d̂ ≥ 0.5 π − é 🙂"), "crate_1 d̂ ≥ 0.5 π − é 🙂");
  EXPECT_EQ(printable(""), "");
  EXPECT_EQ(printable("a\\b"), "a\\b");
}

TEST(Printable, ControlCharactersAreEscaped) {
  EXPECT_EQ(printable("a\tb\nc"), "a\\x09b\\x0Ac");
  EXPECT_EQ(printable(std::string("x\0y", 3)), "x\\x00y");
  EXPECT_EQ(printable("\x7f"), "\\x7F");
  EXPECT_EQ(printable("\xc2\x85"), "\\xC2\\x85");  // U+0085, a C1 control
}

TEST(Printable, BytesThatAreNotUtf8AreEscaped) {
  EXPECT_EQ(printable("ab\xff"), "ab\\xFF");
  EXPECT_EQ(printable("\xc3"), "\\xC3");                   // truncated sequence
  EXPECT_EQ(printable("\xc0\xaf"), "\\xC0\\xAF");          // overlong '/'
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xED\\xA0\\x80");  // a surrogate
  EXPECT_EQ(printable("\xe2\x89"), "\\xE2\\x89");          // ≥ cut short
}

TEST(Printable, Utf8ValidityAndControlCharacters) {
  EXPECT_TRUE(is_valid_utf8("d̂ ≥ 🙂"));
  EXPECT_FALSE(is_valid_utf8("a\xff"));
  EXPECT_TRUE(has_control_character("a\x07"));
  EXPECT_FALSE(has_control_character("d̂ ≥"));
}

TEST(Printable, BlankMeansNothingVisible) {
  EXPECT_TRUE(is_blank(""));
  EXPECT_TRUE(is_blank(" \t\n"));
  EXPECT_TRUE(is_blank("\xc2\xa0\xe3\x80\x80\xef\xbb\xbf"));  // no-break space, ideographic space, BOM
  EXPECT_TRUE(is_blank("\xe2\x80\x8b"));                      // zero-width space
  EXPECT_FALSE(is_blank(" a "));
  EXPECT_FALSE(is_blank("\xff"));
}

}  // namespace
}  // namespace stiffsoft
