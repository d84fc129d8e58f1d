// engine/core/strings: exact values of the shared text utilities.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "engine/core/strings.h"

namespace gmg {
namespace {

const std::string kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

TEST(Strings, TrimRemovesAsciiWhiteSpaceOnly) {
  EXPECT_EQ(trim("  a b \t\r\n"), "a b");
  EXPECT_EQ(trim("\f\va\v\f"), "a");
  EXPECT_EQ(trim(""), "");
  EXPECT_EQ(trim(" \t\r\n\f\v"), "");
  EXPECT_EQ(trim("x"), "x");
  // A no-break space (U+00A0, C2 A0) is not ASCII white space: kept.
  EXPECT_EQ(trim("\xC2\xA0x "), "\xC2\xA0x");
}

TEST(Strings, IsAsciiSpace) {
  for (char c : {' ', '\t', '\r', '\n', '\f', '\v'}) EXPECT_TRUE(is_ascii_space(c)) << static_cast<int>(c);
  for (char c : {'a', '\0', '_', '\xA0', '\xC2'}) EXPECT_FALSE(is_ascii_space(c)) << static_cast<int>(c);
}

TEST(Strings, AsciiLowerLeavesOtherBytes) {
  EXPECT_EQ(ascii_lower("AbC-XyZ 09"), "abc-xyz 09");
  EXPECT_EQ(ascii_lower("\xC3\x84"
                        "B"),
            "\xC3\x84"
            "b");  // U+00C4 stays as it is
  EXPECT_EQ(ascii_lower(""), "");
  EXPECT_EQ(ascii_lower("@[`{"), "@[`{");  // the neighbours of A-Z and a-z
}

TEST(Strings, EndsWithCaseInsensitive) {
  EXPECT_TRUE(ends_with_ci("take.TextGrid", ".textgrid"));
  EXPECT_TRUE(ends_with_ci("X.TSV", ".tsv"));
  EXPECT_TRUE(ends_with_ci("abc", ""));
  EXPECT_FALSE(ends_with_ci("a", ".tsv"));
  EXPECT_FALSE(ends_with_ci("take.tsv.bak", ".tsv"));
}

TEST(Strings, SplitTrimmedDropsEmptyPieces) {
  EXPECT_EQ(split_trimmed("a, b,,c ", ','), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(split_trimmed("RightHand", ','), (std::vector<std::string>{"RightHand"}));
  EXPECT_TRUE(split_trimmed("", ',').empty());
  EXPECT_TRUE(split_trimmed(" , ,", ',').empty());
  EXPECT_EQ(split_trimmed("a b;c", ';'), (std::vector<std::string>{"a b", "c"}));
}

TEST(Strings, SplitLines) {
  using Lines = std::vector<std::string>;
  EXPECT_EQ(split_lines("a\r\nb\n\nc"), (Lines{"a", "b", "", "c"}));
  EXPECT_EQ(split_lines("a\n"), (Lines{"a"}));  // no empty line after the last "\n"
  EXPECT_EQ(split_lines("a\n\n"), (Lines{"a", ""}));
  EXPECT_EQ(split_lines("\n"), (Lines{""}));
  EXPECT_EQ(split_lines(""), Lines{});
  EXPECT_EQ(split_lines("a\r"), (Lines{"a"}));        // a final CR of a CRLF file cut short
  EXPECT_EQ(split_lines("a\rb\n"), (Lines{"a\rb"}));  // only a line's last CR goes
}

TEST(Strings, Utf8BomNeedsAllThreeBytes) {
  EXPECT_FALSE(has_utf8_bom(""));
  EXPECT_FALSE(has_utf8_bom("\xEF"));
  EXPECT_FALSE(has_utf8_bom("\xEF\xBB"));
  EXPECT_TRUE(has_utf8_bom("\xEF\xBB\xBF"));
  EXPECT_TRUE(has_utf8_bom("\xEF\xBB\xBFHIERARCHY"));
  EXPECT_FALSE(has_utf8_bom("\xEF\xBF\xBDHIERARCHY"));  // U+FFFD starts with EF too
  EXPECT_FALSE(has_utf8_bom("x\xEF\xBB\xBF"));

  EXPECT_EQ(strip_utf8_bom("\xEF\xBB\xBFHIERARCHY"), "HIERARCHY");
  EXPECT_EQ(strip_utf8_bom("\xEF\xBB\xBF"), "");
  EXPECT_EQ(strip_utf8_bom("\xEF\xBB"
                           "x"),
            "\xEF\xBB"
            "x");
  EXPECT_EQ(strip_utf8_bom("\xEF\xBF\xBD"), "\xEF\xBF\xBD");
  EXPECT_EQ(strip_utf8_bom("HIERARCHY"), "HIERARCHY");
}

TEST(Strings, ParseNumber) {
  EXPECT_EQ(parse_number("1.5"), 1.5);
  EXPECT_EQ(parse_number(" -2 "), -2.0);
  EXPECT_EQ(parse_number("+3e-1"), 0.3);
  EXPECT_EQ(parse_number(".5"), 0.5);
  EXPECT_EQ(parse_number("\t0\r\n"), 0.0);
  for (const char* bad : {"", "  ", "+", "+-1", "++1", "1.5x", "x1", "1 2", "nan", "inf", "-inf", "1e309", "0x10"})
    EXPECT_FALSE(parse_number(bad).has_value()) << "'" << bad << "'";
}

TEST(Strings, FormatNumberIsShortest) {
  EXPECT_EQ(format_number(0.2), "0.2");
  EXPECT_EQ(format_number(0.1 + 0.2), "0.30000000000000004");  // 0.3 would read back as another double
  EXPECT_EQ(format_number(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(format_number(1e-5), "1e-05");
  EXPECT_EQ(format_number(20231009), "20231009");
  EXPECT_EQ(format_number(0.0), "0");
  EXPECT_EQ(format_number(-1.5), "-1.5");
  // Whole numbers: plain digits when they are no longer than the exponent form ("%.1g" of 100
  // is "1e+02", which reads back too).
  EXPECT_EQ(format_number(100), "100");
  EXPECT_EQ(format_number(1500), "1500");
  EXPECT_EQ(format_number(-300), "-300");
  EXPECT_EQ(format_number(1e5), "1e+05");
  EXPECT_EQ(format_number(1e21), "1e+21");
  EXPECT_EQ(format_number(0.0001), "0.0001");
  EXPECT_EQ(format_number(std::nan("")), "nan");
  EXPECT_EQ(format_number(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_number(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(Strings, FormatNumberRoundTrips) {
  for (double v : {0.2, 0.1 + 0.2, 1.0 / 3.0, 2.0 / 3.0, 1e-300, 4.9e-324, 1.7976931348623157e308, -123.456,
                   29.97002997002997, 1.0 / 30.0}) {
    const std::string text = format_number(v);
    double back = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), back);
    EXPECT_TRUE(r.ec == std::errc() && r.ptr == text.data() + text.size()) << text;
    EXPECT_EQ(back, v) << text;
    // Shortest: one significant digit fewer no longer reads back.
    std::size_t digits = 0;  // significant: leading zeros ("0.0333") do not count
    for (char c : text.substr(0, text.find('e'))) digits += (c >= '1' && c <= '9') || (c == '0' && digits > 0);
    if (digits > 1 && v != 0) {
      char shorter[400];
      std::snprintf(shorter, sizeof shorter, "%.*g", static_cast<int>(digits) - 1, v);
      EXPECT_NE(std::strtod(shorter, nullptr), v) << text << " vs " << shorter;
    }
  }
}

// format_fixed6 against the C library's printf (glibc rounds the exact binary value, ties to even).
std::string printf_fixed6(double v) {
  char buf[kFixed6Chars];
  std::snprintf(buf, sizeof buf, "%.6f", v);
  const std::string text = buf;
  return text == "-0.000000" ? "0.000000" : text;
}

std::string fixed6(double v) {
  char buf[kFixed6Chars];
  return std::string(buf, format_fixed6(v, buf));
}

TEST(Strings, FormatFixed6IsPrintfs) {
  EXPECT_EQ(fixed6(0.0), "0.000000");
  EXPECT_EQ(fixed6(-0.0), "0.000000");
  EXPECT_EQ(fixed6(-4e-7), "0.000000");  // rounds to zero: no sign
  EXPECT_EQ(fixed6(-6e-7), "-0.000001");
  EXPECT_EQ(fixed6(1.5), "1.500000");
  EXPECT_EQ(fixed6(-123.4567894), "-123.456789");
  EXPECT_EQ(fixed6(999999.9999996), "1000000.000000");
  // Exact ties: k/128 for odd k is a half-integer number of millionths; printf rounds to even.
  EXPECT_EQ(fixed6(1.0 / 128), "0.007812");    // 7812.5 millionths
  EXPECT_EQ(fixed6(3.0 / 128), "0.023438");    // 23437.5
  EXPECT_EQ(fixed6(-5.0 / 128), "-0.039062");  // -39062.5
  EXPECT_EQ(fixed6(1e300).substr(0, 4), "1000");
  EXPECT_EQ(fixed6(1e300).size(), 301u + 7u);
  EXPECT_EQ(fixed6(std::numeric_limits<double>::infinity()), "inf");

  std::vector<double> values;
  for (int k = -4000; k <= 4000; ++k) values.push_back(k / 128.0);  // every tie of 1/128 steps and its neighbours
  for (int k = -1000; k <= 1000; ++k) {
    const double half = (k + 0.5) / 1e6;  // the nearest doubles to a tie in decimal
    values.push_back(half);
    values.push_back(std::nextafter(half, 1e9));
    values.push_back(std::nextafter(half, -1e9));
  }
  std::uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return state;
  };
  for (int i = 0; i < 200000; ++i) {  // magnitudes from 1e-9 to 1e8, both signs, and random bit patterns
    const double unit = static_cast<double>(next() >> 11) * 0x1p-53;
    const double magnitude = std::pow(10.0, -9.0 + 17.0 * static_cast<double>(next() >> 11) * 0x1p-53);
    values.push_back((next() & 1 ? -1.0 : 1.0) * unit * magnitude);
    const std::uint64_t bits = next();
    double any = 0;
    std::memcpy(&any, &bits, sizeof any);
    if (std::isfinite(any)) values.push_back(any);
  }
  for (double boundary : {1e6, 1e12 / 1e6, 999999.9999995, 1e-6, 5e-7, 4.9999999999999e-7})
    for (double v : {boundary, -boundary, std::nextafter(boundary, 0.0), std::nextafter(boundary, 2e6)})
      values.push_back(v);
  std::size_t differing = 0;
  for (double v : values)
    if (fixed6(v) != printf_fixed6(v) && ++differing <= 5)
      ADD_FAILURE() << v << ": " << fixed6(v) << " vs " << printf_fixed6(v);
  EXPECT_EQ(differing, 0u) << "of " << values.size();
}

TEST(Strings, ToValidUtf8) {
  const std::string r = kReplacement;
  EXPECT_EQ(to_valid_utf8("plain ascii"), "plain ascii");
  EXPECT_EQ(to_valid_utf8("caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80"), "caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80");
  EXPECT_EQ(to_valid_utf8("caf\xE9"), "caf" + r);  // Latin-1 e-acute
  EXPECT_EQ(to_valid_utf8("\xE9t\xE9"), r + "t" + r);
  EXPECT_EQ(to_valid_utf8("\xC0\xAF"), r + r);                       // overlong "/"
  EXPECT_EQ(to_valid_utf8("\xE0\x80\xAF"), r + r + r);               // overlong "/", 3 bytes
  EXPECT_EQ(to_valid_utf8("\xF0\x80\x80\xAF"), r + r + r + r);       // overlong "/", 4 bytes
  EXPECT_EQ(to_valid_utf8("\xED\xA0\x80"), r + r + r);               // surrogate U+D800
  EXPECT_EQ(to_valid_utf8("\xED\x9F\xBF"), "\xED\x9F\xBF");          // U+D7FF, just below
  EXPECT_EQ(to_valid_utf8("\xF4\x8F\xBF\xBF"), "\xF4\x8F\xBF\xBF");  // U+10FFFF
  EXPECT_EQ(to_valid_utf8("\xF4\x90\x80\x80"), r + r + r + r);       // beyond U+10FFFF
  EXPECT_EQ(to_valid_utf8("a\xE2\x82"), "a" + r + r);                // cut short at the end
  EXPECT_EQ(to_valid_utf8("\x80"), r);                               // lone continuation byte
  EXPECT_EQ(to_valid_utf8(std::string("a\0b", 3)), std::string("a\0b", 3));
}

// Code points taken from the Unicode standard's examples (U+00E9, U+20AC, U+1F600) and the edges
// of the ranges RFC 3629 allows.
TEST(Strings, DecodeUtf8WellFormed) {
  struct Case {
    std::string bytes;
    char32_t code_point;
  };
  const Case cases[] = {
      {"A", 0x41},
      {std::string("\0", 1), 0x0},
      {"\x7F", 0x7F},
      {"\xC2\x80", 0x80},
      {"\xC3\xA9", 0xE9},
      {"\xDF\xBF", 0x7FF},
      {"\xE0\xA0\x80", 0x800},
      {"\xE2\x82\xAC", 0x20AC},
      {"\xED\x9F\xBF", 0xD7FF},
      {"\xEE\x80\x80", 0xE000},
      {"\xEF\xBF\xBF", 0xFFFF},
      {"\xF0\x90\x80\x80", 0x10000},
      {"\xF0\x9F\x98\x80", 0x1F600},
      {"\xF4\x8F\xBF\xBF", 0x10FFFF},
  };
  for (const Case& c : cases) {
    const auto got = decode_utf8(c.bytes, 0);
    ASSERT_TRUE(got.has_value()) << std::hex << static_cast<std::uint32_t>(c.code_point);
    EXPECT_EQ(got->code_point, c.code_point);
    EXPECT_EQ(got->length, c.bytes.size());
  }
  // Decoding starts where it is told to.
  const auto e = decode_utf8("caf\xC3\xA9", 3);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->code_point, 0xE9u);
}

TEST(Strings, DecodeUtf8RejectsOverlongSurrogatesAndTruncation) {
  const char* const rejected[] = {
      "\xC0\xAF",          // "/" in two bytes (overlong)
      "\xC1\xBF",          // U+7F in two bytes
      "\xE0\x80\xAF",      // "/" in three bytes
      "\xE0\x9F\xBF",      // U+7FF in three bytes
      "\xF0\x80\x80\xAF",  // "/" in four bytes
      "\xF0\x8F\xBF\xBF",  // U+FFFF in four bytes
      "\xED\xA0\x80",      // U+D800, a surrogate
      "\xED\xBF\xBF",      // U+DFFF
      "\xF4\x90\x80\x80",  // U+110000, beyond Unicode
      "\xF5\x80\x80\x80",  // a lead byte no character has
      "\xFF",
      "\x80",  // a continuation byte alone
      "\xBF",
      "\xC3",  // cut short by the end
      "\xE2\x82",
      "\xF0\x9F\x98",
      "\xC3(",  // cut short by a byte that does not continue it
      "\xE2\x82(",
  };
  for (const char* bytes : rejected) EXPECT_FALSE(decode_utf8(bytes, 0).has_value()) << ::testing::PrintToString(bytes);
  EXPECT_FALSE(decode_utf8("", 0).has_value());
  EXPECT_FALSE(decode_utf8("ab", 2).has_value());  // at the end
}

TEST(Strings, EscapeNonprintableKeepsTextAndEscapesTheRest) {
  EXPECT_EQ(escape_nonprintable("take.bvh: line 3 \\ ok"), "take.bvh: line 3 \\ ok");
  EXPECT_EQ(escape_nonprintable("caf\xC3\xA9 \xE2\x82\xAC"), "caf\xC3\xA9 \xE2\x82\xAC");  // UTF-8 stays
  EXPECT_EQ(escape_nonprintable("a\nb\rc\td"), "a\\nb\\rc\\td");
  EXPECT_EQ(escape_nonprintable(std::string("\x1B[2J\x07\0\x7F", 7)), "\\x1b[2J\\x07\\x00\\x7f");
  EXPECT_EQ(escape_nonprintable("caf\xE9"), "caf\\xe9");  // Latin-1: not UTF-8
  EXPECT_EQ(escape_nonprintable("\xC2\x9B"
                                "1m"),
            "\\u009b1m");                                             // C1 CSI, a terminal escape
  EXPECT_EQ(escape_nonprintable("\xED\xA0\x80"), "\\xed\\xa0\\x80");  // a surrogate, byte by byte
  EXPECT_EQ(escape_nonprintable(""), "");
}

TEST(Strings, EditDistanceCountsASwapOfNeighboursAsOne) {
  EXPECT_EQ(edit_distance("build", "build"), 0u);
  EXPECT_EQ(edit_distance("biuld", "build"), 1u);  // a swap
  EXPECT_EQ(edit_distance("buld", "build"), 1u);   // a deletion
  EXPECT_EQ(edit_distance("buiild", "build"), 1u);
  EXPECT_EQ(edit_distance("bxild", "build"), 1u);
  EXPECT_EQ(edit_distance("render", "reenact"), 4u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("ca", "abc"), 3u);  // optimal string alignment: no edit of a swapped pair
}

TEST(Strings, NearestNameSuggestsOnlyPlausibleTypos) {
  const std::vector<std::string> commands = {"build", "inspect", "reenact", "evaluate", "render"};
  EXPECT_EQ(nearest_name("biuld", commands), "build");
  EXPECT_EQ(nearest_name("REENACT", commands), "reenact");  // case alone
  EXPECT_EQ(nearest_name("evalute", commands), "evaluate");
  EXPECT_EQ(nearest_name("build", commands), std::nullopt);  // no typo
  EXPECT_EQ(nearest_name("xyz", commands), std::nullopt);
  EXPECT_EQ(nearest_name("-x", {"-o", "-j"}), std::nullopt);  // 1 edit of 2 letters is a guess
  EXPECT_EQ(nearest_name("--grpah", {"--graph", "--audio"}), "--graph");
  EXPECT_EQ(did_you_mean("l_pm", {"l_pn", "l_cn"}), " (did you mean 'l_pn'?)");  // the first of equals
  EXPECT_EQ(did_you_mean("zzzz", {"l_pn"}), "");
}

}  // namespace
}  // namespace gmg
