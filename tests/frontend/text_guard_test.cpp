// frontend/text_guard.h: utf8_prefix never cuts a UTF-8 sequence in two, and
// what messages show of a long value (frontend::shown) stays valid UTF-8.
// Oracle: the byte lengths of the characters, worked out by hand.
#include <gtest/gtest.h>

#include <string>

#include "frontend/text_guard.h"
#include "frontend/yaml_reader.h"

namespace mbfe::frontend {
namespace {

TEST(Utf8Prefix, CutsBeforeACharacterItWouldSplit) {
  const std::string e_acute = "\xC3\xA9";        // 2 bytes
  const std::string euro = "\xE2\x82\xAC";       // 3 bytes
  const std::string emoji = "\xF0\x9F\x98\x80";  // 4 bytes
  EXPECT_EQ(utf8_prefix("abcdef", 4), "abcd");
  EXPECT_EQ(utf8_prefix("abc", 10), "abc");
  EXPECT_EQ(utf8_prefix("a" + e_acute + "b", 2), "a");  // the cut falls after é's first byte
  EXPECT_EQ(utf8_prefix("a" + e_acute + "b", 3), "a" + e_acute);
  EXPECT_EQ(utf8_prefix(euro + euro, 4), euro);
  EXPECT_EQ(utf8_prefix(euro + euro, 5), euro);
  EXPECT_EQ(utf8_prefix(euro + euro, 6), euro + euro);
  for (std::size_t n = 0; n < 4; ++n) EXPECT_EQ(utf8_prefix(emoji + "x", n), "") << n;
  EXPECT_EQ(utf8_prefix(emoji + "x", 4), emoji);
}

TEST(Utf8Prefix, WhatMessagesShowOfALongValueIsValidUtf8) {
  // 30 euro signs, 90 bytes: shown() keeps 40 bytes, which is 13 signs and a
  // third; it keeps 13 (39 bytes) and says how long the value was.
  std::string euros;
  for (int i = 0; i < 30; ++i) euros += "\xE2\x82\xAC";
  const std::string s = shown(euros);
  EXPECT_EQ(s, euros.substr(0, 39) + "... (90 characters)");
  EXPECT_FALSE(find_non_text(s).has_value()) << s;
}

}  // namespace
}  // namespace mbfe::frontend
