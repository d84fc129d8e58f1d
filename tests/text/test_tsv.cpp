// Tests of text/tsv: GENEA TSV transcripts.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/core/error.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"
#include "text/transcript.h"

namespace {

using gmg::testing::error_of;
using gmg::testing::TempDir;
using gmg::testing::write_text;
namespace tx = gmg::text;

std::vector<tx::Word> tsv_from(const TempDir& dir, const std::string& content, const std::string& name = "t.tsv") {
  write_text(dir.file(name), content);
  return tx::read_tsv(dir.file(name));
}

TEST(TextTsv, ReadsNormalFile) {
  TempDir dir;
  auto words = tsv_from(dir, "0.5\t0.9\thello\n1.0\t1.25\tworld\n");
  ASSERT_EQ(words.size(), 2u);
  EXPECT_DOUBLE_EQ(words[0].start, 0.5);
  EXPECT_DOUBLE_EQ(words[0].end, 0.9);
  EXPECT_EQ(words[0].text, "hello");
  EXPECT_DOUBLE_EQ(words[1].start, 1.0);
  EXPECT_DOUBLE_EQ(words[1].end, 1.25);
  EXPECT_EQ(words[1].text, "world");
}

TEST(TextTsv, WordWithSpacesAndTabsKeepsEverythingAfterSecondTab) {
  TempDir dir;
  auto words = tsv_from(dir, "0\t1\ta lot\n1\t2\tone\ttwo \n");
  ASSERT_EQ(words.size(), 2u);
  EXPECT_EQ(words[0].text, "a lot");
  EXPECT_EQ(words[1].text, "one\ttwo");
}

TEST(TextTsv, CrlfBomBlankLinesAndLaughter) {
  TempDir dir;
  auto words = tsv_from(dir,
                        "\xEF\xBB\xBF"
                        "0.1\t0.2\tHi\r\n\r\n   \r\n0.3\t0.6\t#\r\n0.7\t0.8\tthere\r\n");
  ASSERT_EQ(words.size(), 3u);
  EXPECT_EQ(words[0].text, "Hi");  // no BOM bytes, no CR
  EXPECT_DOUBLE_EQ(words[0].start, 0.1);
  EXPECT_EQ(words[1].text, "#");
  EXPECT_EQ(words[2].text, "there");
  EXPECT_DOUBLE_EQ(words[2].end, 0.8);
}

TEST(TextTsv, SortedByStartStably) {
  TempDir dir;
  auto words = tsv_from(dir, "2\t3\tc\n1\t2\ta\n1\t1.5\tb\n");
  ASSERT_EQ(words.size(), 3u);
  EXPECT_EQ(words[0].text, "a");
  EXPECT_EQ(words[1].text, "b");
  EXPECT_EQ(words[2].text, "c");
}

TEST(TextTsv, EmptyFileIsZeroWords) {
  TempDir dir;
  EXPECT_TRUE(tsv_from(dir, "").empty());
  EXPECT_TRUE(tsv_from(dir, "\n\r\n").empty());
  // A line with an empty word is silence.
  auto words = tsv_from(dir, "0\t1\t \n1\t2\tyes\n");
  ASSERT_EQ(words.size(), 1u);
  EXPECT_EQ(words[0].text, "yes");
}

TEST(TextTsv, EndBeforeStartNamesFileAndLine) {
  TempDir dir;
  std::string msg = error_of([&] { tsv_from(dir, "0\t1\ta\n1\t2\tb\n3\t2.5\tc\n"); });
  EXPECT_CONTAINS(msg, dir.file("t.tsv"));
  EXPECT_CONTAINS(msg, "line 3");
  EXPECT_CONTAINS(msg, "before it starts");
}

TEST(TextTsv, NonNumericTime) {
  TempDir dir;
  std::string msg = error_of([&] { tsv_from(dir, "0\t1\ta\nabc\t2\tb\n"); });
  EXPECT_CONTAINS(msg, "t.tsv: line 2");
  EXPECT_CONTAINS(msg, "not a number");
  msg = error_of([&] { tsv_from(dir, "0\t1.5x\ta\n"); });
  EXPECT_CONTAINS(msg, "t.tsv: line 1: end time \"1.5x\" is not a number");
}

TEST(TextTsv, NanInfAndNegativeTimes) {
  TempDir dir;
  std::string msg = error_of([&] { tsv_from(dir, "nan\t1\ta\n"); });
  EXPECT_CONTAINS(msg, "t.tsv: line 1: start time \"nan\" is not a finite number");
  msg = error_of([&] { tsv_from(dir, "0\t1\ta\n1\tinf\tb\n"); });
  EXPECT_CONTAINS(msg, "t.tsv: line 2: end time \"inf\" is not a finite number");
  msg = error_of([&] { tsv_from(dir, "0\t1\ta\n1\t-Infinity\tb\n"); });
  EXPECT_CONTAINS(msg, "t.tsv: line 2: end time \"-Infinity\" is not a finite number");
  msg = error_of([&] { tsv_from(dir, "-0.5\t1\ta\n"); });
  EXPECT_CONTAINS(msg, "t.tsv: line 1: negative start time -0.5");
}

TEST(TextTsv, TooFewFields) {
  TempDir dir;
  std::string msg = error_of([&] { tsv_from(dir, "0\t1\ta\n\n1\t2\n"); });
  EXPECT_CONTAINS(msg, "t.tsv: line 3");
  EXPECT_CONTAINS(msg, "2 field(s)");
}

TEST(TextTsv, MissingFileNamesIt) {
  TempDir dir;
  EXPECT_EQ(error_of([&] { tx::read_tsv(dir.file("nope.tsv")); }),
            dir.file("nope.tsv") + ": cannot open (No such file or directory)");
}

}  // namespace
