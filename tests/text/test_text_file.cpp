// Tests of text/text_file: any encoding a transcript tool writes, read as UTF-8.
#include <gtest/gtest.h>

#include <string>

#include "engine/core/error.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"
#include "tests/text/text_test_util.h"
#include "text/text_file.h"

namespace {

using gmg::testing::error_of;
using gmg::testing::TempDir;
using gmg::testing::to_utf16;
using gmg::testing::write_text;
using gmg::text::detail::decode_to_utf8;
using gmg::text::detail::read_text_file;

TEST(TextFile, Utf8PassesThroughAndLosesItsBom) {
  EXPECT_EQ(decode_to_utf8("caf\xC3\xA9\r\n", "t"), "caf\xC3\xA9\r\n");
  EXPECT_EQ(decode_to_utf8("\xEF\xBB\xBF"
                           "abc",
                           "t"),
            "abc");
  EXPECT_EQ(decode_to_utf8("\xEF\xBB\xBF", "t"), "");
  EXPECT_EQ(decode_to_utf8("", "t"), "");
  // One or two bytes of a mark are not a mark: the text is left alone.
  EXPECT_EQ(decode_to_utf8("\xEF\xBB"
                           "a",
                           "t"),
            "\xEF\xBB"
            "a");
  EXPECT_EQ(decode_to_utf8("\xEF"
                           "ab",
                           "t"),
            "\xEF"
            "ab");
}

TEST(TextFile, Utf16WithMark) {
  EXPECT_EQ(decode_to_utf8(to_utf16("Hi\n", true), "t"), "Hi\n");
  EXPECT_EQ(decode_to_utf8(to_utf16("Hi\n", false), "t"), "Hi\n");
  // U+00E9 (2 UTF-8 bytes), U+20AC (3), and U+1F600 as the surrogate pair D83D DE00 (4).
  EXPECT_EQ(decode_to_utf8(std::string("\xFF\xFE\xE9\x00\xAC\x20\x3D\xD8\x00\xDE", 10), "t"),
            "\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80");
  EXPECT_EQ(decode_to_utf8(std::string("\xFE\xFF\x00\xE9\x20\xAC\xD8\x3D\xDE\x00", 10), "t"),
            "\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80");
}

TEST(TextFile, Utf16UnpairedSurrogatesBecomeReplacement) {
  // A high surrogate followed by "A", and a lone low surrogate.
  EXPECT_EQ(decode_to_utf8(std::string("\xFF\xFE\x3D\xD8\x41\x00\x00\xDE", 8), "t"),
            "\xEF\xBF\xBD"
            "A"
            "\xEF\xBF\xBD");
  // A high surrogate at the very end.
  EXPECT_EQ(decode_to_utf8(std::string("\xFF\xFE\x41\x00\x3D\xD8", 6), "t"), "A\xEF\xBF\xBD");
}

TEST(TextFile, Utf16WithoutMarkWhenTheFirstCharacterIsAscii) {
  EXPECT_EQ(decode_to_utf8(std::string("F\0i\0", 4), "t"), "Fi");
  EXPECT_EQ(decode_to_utf8(std::string("\0F\0i", 4), "t"), "Fi");
}

TEST(TextFile, OddUtf16NamesTheFile) {
  EXPECT_EQ(error_of([] { decode_to_utf8(std::string("\xFF\xFE\x41\x00\x42", 5), "cut.TextGrid"); }),
            "cut.TextGrid: UTF-16 text with an odd number of bytes (truncated file?)");
}

TEST(TextFile, ReadDecodesAndUsesTheReaderWording) {
  TempDir dir;
  write_text(dir.file("w.TextGrid"), to_utf16("File type", true));
  EXPECT_EQ(read_text_file(dir.file("w.TextGrid")), "File type");
  const std::string missing = dir.file("missing.txt");
  EXPECT_EQ(error_of([&] { read_text_file(missing); }), missing + ": cannot open (No such file or directory)");
  EXPECT_EQ(error_of([&] { read_text_file(dir.path().string()); }), dir.path().string() + ": is a folder, not a file");
  write_text(dir.file("odd.txt"), std::string("\xFE\xFF\x00", 3));
  EXPECT_EQ(error_of([&] { read_text_file(dir.file("odd.txt")); }),
            dir.file("odd.txt") + ": UTF-16 text with an odd number of bytes (truncated file?)");
}

}  // namespace
