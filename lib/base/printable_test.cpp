#include "dqskin/error.hpp"

#include <gtest/gtest.h>

namespace {

using dqskin::printable;

TEST(Printable, KeepsPlainTextAndUtf8Letters) {
  EXPECT_EQ(printable("node 3: rotation is a zero quaternion"), "node 3: rotation is a zero quaternion");
  EXPECT_EQ(printable("Fuß/Ölfläche 骨.glb 🦊"), "Fuß/Ölfläche 骨.glb 🦊");
}

TEST(Printable, EscapesLineBreaksAndTerminalEscapes) {
  EXPECT_EQ(printable("two\nlines\r\tand \x1b[31mred\x1b[0m"), "two\\nlines\\r\\tand \\x1b[31mred\\x1b[0m");
  EXPECT_EQ(printable(std::string_view("nul\0bell\x07" "del\x7f", 13)), "nul\\x00bell\\x07del\\x7f");
}

TEST(Printable, EscapesBytesThatAreNotUtf8) {
  EXPECT_EQ(printable("\xff\xfe"), "\\xff\\xfe");
  EXPECT_EQ(printable("cut \xe2\x82"), "cut \\xe2\\x82");              // a sequence cut short
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");                      // overlong '/'
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");              // a UTF-16 surrogate
  EXPECT_EQ(printable("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");      // above U+10FFFF
  EXPECT_EQ(printable("\xe2\x82\xac ok \xe2\x28\xa1"), "\xe2\x82\xac ok \\xe2(\\xa1");
}

TEST(Printable, EscapesCodePointsThatMoveOrReorderText) {
  EXPECT_EQ(printable("\xc2\x9b" "2J"), "\\u009b2J");                  // C1 CSI
  EXPECT_EQ(printable("abc\xe2\x80\xae" "fdp.exe"), "abc\\u202efdp.exe");  // right-to-left override
  EXPECT_EQ(printable("a\xe2\x80\xa8" "b"), "a\\u2028b");               // line separator
}

TEST(Printable, OutputIsAlwaysOnePrintableLine) {
  std::string all;
  for (int c = 0; c < 256; ++c) all += char(c);
  const std::string out = printable(all);
  for (char c : out) EXPECT_TRUE(uint8_t(c) >= 0x20 && uint8_t(c) != 0x7F) << int(uint8_t(c));
}

}  // namespace
