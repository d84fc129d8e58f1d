// engine/core/csv: the RFC 4180 subset the batch manifests and records use.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/csv.h"
#include "engine/core/error.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using Fields = std::vector<std::string>;

std::string parse_error(const std::string& text, const std::string& path) {
  try {
    csv_parse(text, path);
  } catch (const Error& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(CsvParse, PlainFieldsAreTrimmedAndRowsKeepTheirLine) {
  const auto rows = csv_parse("a, b ,c\n  x,,\t y\t\n", "t.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].line, 1);
  EXPECT_EQ(rows[0].fields, (Fields{"a", "b", "c"}));
  EXPECT_EQ(rows[1].line, 2);
  EXPECT_EQ(rows[1].fields, (Fields{"x", "", "y"}));
}

TEST(CsvParse, QuotedFieldsKeepCommasSpacesLineBreaksAndEscapedQuotes) {
  const auto rows = csv_parse("\"a,b\",\" padded \",\"say \"\"hi\"\"\"\n\"two\nlines\",z\nnext\n", "t.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].fields, (Fields{"a,b", " padded ", "say \"hi\""}));
  EXPECT_EQ(rows[1].fields, (Fields{"two\nlines", "z"}));
  EXPECT_EQ(rows[1].line, 2);
  EXPECT_EQ(rows[2].line, 4);  // the quoted line break counts
  EXPECT_EQ(rows[2].fields, Fields{"next"});
}

TEST(CsvParse, SpaceBeforeAnOpeningQuoteAndTextAfterAClosingOneAreDropped) {
  const auto rows = csv_parse("  \"q\" junk,b\n", "t.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].fields, (Fields{"q", "b"}));
}

TEST(CsvParse, CrlfLineEnds) {
  const auto rows = csv_parse("a,b\r\nc,d\r\n\r\ne,f", "t.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].fields, (Fields{"a", "b"}));
  EXPECT_EQ(rows[1].fields, (Fields{"c", "d"}));
  EXPECT_EQ(rows[2].fields, (Fields{"e", "f"}));
  EXPECT_EQ(rows[2].line, 4);
}

TEST(CsvParse, CommentAndBlankLinesAreSkippedButCounted) {
  const auto rows = csv_parse("# header comment\n\nstem,wav\n#x,y\nA,a.wav\n", "t.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].fields, (Fields{"stem", "wav"}));
  EXPECT_EQ(rows[0].line, 3);
  EXPECT_EQ(rows[1].fields, (Fields{"A", "a.wav"}));
  EXPECT_EQ(rows[1].line, 5);
}

TEST(CsvParse, ByteOrderMarkIsSkipped) {
  const auto rows = csv_parse("\xEF\xBB\xBFstem,wav\n", "t.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].fields, (Fields{"stem", "wav"}));
  // A BOM then a comment: the comment is still recognised.
  EXPECT_TRUE(csv_parse("\xEF\xBB\xBF# only a comment\n", "t.csv").empty());
}

TEST(CsvParse, UnterminatedQuoteNamesTheFileAndTheRowsLine) {
  EXPECT_EQ(parse_error("a,b\n# c\nx,\"open\nstill open\n", "pairs.csv"),
            "pairs.csv: line 3: unterminated quoted field");
  EXPECT_EQ(parse_error("\"", "m.csv"), "m.csv: line 1: unterminated quoted field");
}

TEST(CsvReadFile, ReadsAFileAndNamesItInErrors) {
  testing::TempDir dir;
  testing::write_text(dir.file("ok.csv"), "a,\"b\"\n");
  const auto rows = csv_read_file(dir.file("ok.csv"));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].fields, (Fields{"a", "b"}));
  testing::write_text(dir.file("bad.csv"), "ok\n\"x\n");
  try {
    csv_read_file(dir.file("bad.csv"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), dir.file("bad.csv") + ": line 2: unterminated quoted field");
  }
  EXPECT_THROW(csv_read_file(dir.file("missing.csv")), Error);
}

TEST(CsvWrite, QuotesOnlyWhenNeeded) {
  EXPECT_EQ(csv_field("plain"), "plain");
  EXPECT_EQ(csv_field(""), "");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field("cr\r"), "\"cr\r\"");
  EXPECT_EQ(csv_field(" lead"), "\" lead\"");
  EXPECT_EQ(csv_field("trail "), "\"trail \"");
  EXPECT_EQ(csv_field("in side"), "in side");
  EXPECT_EQ(csv_line({"t1", "", "a,b"}), "t1,,\"a,b\"\n");
  EXPECT_EQ(csv_line({}), "\n");
}

TEST(CsvWrite, WrittenLinesReadBack) {
  const Fields f = {"x", " y ", "a,\"b\"", "l1\r\nl2", ""};
  const auto rows = csv_parse(csv_line(f) + csv_line({"second"}), "t.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].fields, f);
  EXPECT_EQ(rows[1].fields, Fields{"second"});
}

}  // namespace
}  // namespace gmg
