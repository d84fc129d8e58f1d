// Tests of text/textgrid: Praat TextGrid transcripts, long and short formats, any encoding.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"
#include "tests/text/text_test_util.h"
#include "text/transcript.h"

namespace {

using gmg::testing::error_of;
using gmg::testing::TempDir;
using gmg::testing::write_text;
namespace tx = gmg::text;
using gmg::testing::kLongTextGrid;
using gmg::testing::replace_once;
using gmg::testing::to_utf16;

TEST(TextGrid, LongFormatWordsTierSecondSilenceDropped) {
  TempDir dir;
  write_text(dir.file("a.TextGrid"), kLongTextGrid);
  auto words = tx::read_textgrid(dir.file("a.TextGrid"));
  ASSERT_EQ(words.size(), 3u);
  EXPECT_EQ(words[0].text, "very");
  EXPECT_DOUBLE_EQ(words[0].start, 1.0);
  EXPECT_DOUBLE_EQ(words[0].end, 1.5);
  EXPECT_EQ(words[1].text, "big");
  EXPECT_DOUBLE_EQ(words[1].start, 2.0);
  EXPECT_DOUBLE_EQ(words[1].end, 2.25);
  EXPECT_EQ(words[2].text, "say \"hi\"");  // Praat's doubled quotes
}

TEST(TextGrid, CrlfBomAndUtf16ReadTheSame) {
  TempDir dir;
  write_text(dir.file("a.TextGrid"), kLongTextGrid);
  const auto expected = tx::read_textgrid(dir.file("a.TextGrid"));
  std::string crlf;
  for (char c : std::string(kLongTextGrid)) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  const std::vector<std::pair<std::string, std::string>> variants = {
      {"crlf_bom.TextGrid", "\xEF\xBB\xBF" + crlf},
      {"le.TextGrid", to_utf16(crlf, true)},
      {"be.TextGrid", to_utf16(kLongTextGrid, false)},
  };
  for (const auto& [name, bytes] : variants) {
    write_text(dir.file(name), bytes);
    auto words = tx::read_textgrid(dir.file(name));
    ASSERT_EQ(words.size(), expected.size()) << name;
    for (std::size_t i = 0; i < words.size(); ++i) {
      EXPECT_EQ(words[i].text, expected[i].text) << name;
      EXPECT_DOUBLE_EQ(words[i].start, expected[i].start) << name;
      EXPECT_DOUBLE_EQ(words[i].end, expected[i].end) << name;
    }
  }
}

TEST(TextGrid, Utf16NonAsciiTextDecodesToUtf8) {
  TempDir dir;
  std::string grid = replace_once(kLongTextGrid, "\"big\"", "\"caf@\"");
  std::string le = to_utf16(grid, true);
  std::size_t at = le.find(std::string("@\0", 2));
  ASSERT_NE(at, std::string::npos);
  le[at] = '\xE9';  // U+00E9
  le[at + 1] = '\0';
  write_text(dir.file("u.TextGrid"), le);
  auto words = tx::read_textgrid(dir.file("u.TextGrid"));
  ASSERT_EQ(words.size(), 3u);
  EXPECT_EQ(words[1].text, "caf\xC3\xA9");
}

TEST(TextGrid, ShortFormat) {
  TempDir dir;
  write_text(dir.file("s.TextGrid"),
             "File type = \"ooTextFile\"\nObject class = \"TextGrid\"\n\n0\n2.3\n<exists>\n1\n"
             "\"IntervalTier\"\n\"Words\"\n0\n2.3\n3\n0\n1.5\n\"\"\n1.5\n2\n\"hello\"\n2\n2.3\n"
             "\"there\"\n");
  auto words = tx::read_textgrid(dir.file("s.TextGrid"));
  ASSERT_EQ(words.size(), 2u);
  EXPECT_EQ(words[0].text, "hello");
  EXPECT_DOUBLE_EQ(words[0].start, 1.5);
  EXPECT_EQ(words[1].text, "there");
  EXPECT_DOUBLE_EQ(words[1].end, 2.3);
}

TEST(TextGrid, NoWordsTierListsTiers) {
  TempDir dir;
  std::string grid = replace_once(kLongTextGrid, "name = \"words\"", "name = \"syllables\"");
  write_text(dir.file("n.TextGrid"), grid);
  std::string msg = error_of([&] { tx::read_textgrid(dir.file("n.TextGrid")); });
  EXPECT_CONTAINS(msg, dir.file("n.TextGrid"));
  EXPECT_CONTAINS(msg, "no tier named \"words\"");
  EXPECT_CONTAINS(msg, "\"phones\"");
  EXPECT_CONTAINS(msg, "\"syllables\"");
}

TEST(TextGrid, MalformedIntervalGivesLine) {
  TempDir dir;
  // Interval 2 of the words tier loses its xmax line (line 35 of kLongTextGrid; "text" moves up to it).
  std::string grid = replace_once(kLongTextGrid, "            xmax = 1.5 \n", "");
  write_text(dir.file("m.TextGrid"), grid);
  std::string msg = error_of([&] { tx::read_textgrid(dir.file("m.TextGrid")); });
  EXPECT_CONTAINS(msg, "m.TextGrid: line 35");
  EXPECT_CONTAINS(msg, "xmax of interval 2");
}

TEST(TextGrid, NonNumericNanAndReversedTimes) {
  TempDir dir;
  write_text(dir.file("x.TextGrid"), replace_once(kLongTextGrid, "xmax = 2.25", "xmax = 2.2.5"));
  std::string msg = error_of([&] { tx::read_textgrid(dir.file("x.TextGrid")); });
  EXPECT_CONTAINS(msg, "x.TextGrid: line 43");
  EXPECT_CONTAINS(msg, "not a number");

  write_text(dir.file("y.TextGrid"), replace_once(kLongTextGrid, "xmax = 2.25", "xmax = nan"));
  msg = error_of([&] { tx::read_textgrid(dir.file("y.TextGrid")); });
  EXPECT_CONTAINS(msg, "y.TextGrid: line 43");
  EXPECT_CONTAINS(msg, "not a finite number");

  write_text(dir.file("z.TextGrid"), replace_once(kLongTextGrid, "xmax = 2.25", "xmax = 1.75"));
  msg = error_of([&] { tx::read_textgrid(dir.file("z.TextGrid")); });
  EXPECT_CONTAINS(msg, "z.TextGrid: line 42");
  EXPECT_CONTAINS(msg, "before it starts");
}

TEST(TextGrid, NotATextGridAndTruncated) {
  TempDir dir;
  write_text(dir.file("w.TextGrid"), "0\t1\thello\n");
  std::string msg = error_of([&] { tx::read_textgrid(dir.file("w.TextGrid")); });
  EXPECT_CONTAINS(msg, "w.TextGrid: line 1");
  EXPECT_CONTAINS(msg, "File type = \"ooTextFile\"");

  std::string grid(kLongTextGrid);
  write_text(dir.file("t.TextGrid"), grid.substr(0, grid.find("intervals [4]")));
  msg = error_of([&] { tx::read_textgrid(dir.file("t.TextGrid")); });
  EXPECT_CONTAINS(msg, "t.TextGrid: line");
  EXPECT_CONTAINS(msg, "unexpected end of file");
}

TEST(TextGrid, ZeroWordsIsAllowed) {
  TempDir dir;
  write_text(dir.file("e.TextGrid"),
             "File type = \"ooTextFile\"\nObject class = \"TextGrid\"\n\nxmin = 0\nxmax = 2\n"
             "tiers? <exists>\nsize = 1\nitem []:\n    item [1]:\n        class = \"IntervalTier\"\n"
             "        name = \"words\"\n        xmin = 0\n        xmax = 2\n"
             "        intervals: size = 1\n        intervals [1]:\n            xmin = 0\n"
             "            xmax = 2\n            text = \"\"\n");
  EXPECT_TRUE(tx::read_textgrid(dir.file("e.TextGrid")).empty());
}

// ---- Choosing the tier ---------------------------------------------------------------------------

// A long-format TextGrid of interval tiers (name -> one interval each, "" = none) and, when
// `point_tier` is given, a TextTier of that name with one point.
std::string grid_of(const std::vector<std::pair<std::string, std::string>>& tiers, const std::string& point_tier = "") {
  std::string g = "File type = \"ooTextFile\"\nObject class = \"TextGrid\"\n\nxmin = 0\nxmax = 2\ntiers? <exists>\n";
  g += "size = " + std::to_string(tiers.size() + (point_tier.empty() ? 0 : 1)) + "\nitem []:\n";
  int k = 0;
  for (const auto& [name, word] : tiers) {
    g += "    item [" + std::to_string(++k) + "]:\n        class = \"IntervalTier\"\n        name = \"";
    g += name;
    g += "\"\n        xmin = 0\n        xmax = 2\n        intervals: size = 1\n        intervals [1]:\n";
    g += "            xmin = 0.5\n            xmax = 1.25\n            text = \"" + word + "\"\n";
  }
  if (!point_tier.empty())
    g += "    item [" + std::to_string(++k) + "]:\n        class = \"TextTier\"\n        name = \"" + point_tier +
         "\"\n        xmin = 0\n        xmax = 2\n        points: size = 1\n        points [1]:\n" +
         "            number = 1\n            mark = \"beat\"\n";
  return g;
}

TEST(TextGridTier, ANamedTierIsReadExactlyOrIgnoringCaseAndSpaces) {
  TempDir dir;
  write_text(dir.file("a.TextGrid"), kLongTextGrid);
  for (const std::string name : {"phones", " PHONES "}) {
    const auto words = tx::read_textgrid(dir.file("a.TextGrid"), name);
    ASSERT_EQ(words.size(), 1u) << name;  // the phones tier: "" (silence) and "AH0" from 1 to 3.5 s
    EXPECT_EQ(words[0].text, "AH0");
    EXPECT_EQ(words[0].start, 1.0);
    EXPECT_EQ(words[0].end, 3.5);
  }
  // Through the front door, by extension.
  EXPECT_EQ(tx::read_transcript(dir.file("a.TextGrid"), tx::TranscriptFormat::Auto, "phones").at(0).text, "AH0");
}

TEST(TextGridTier, AMissingTierListsTheTiersWithTheirClasses) {
  TempDir dir;
  write_text(dir.file("a.TextGrid"), grid_of({{"words", "hi"}, {"phones", "HH"}}, "beats"));
  const std::string msg = error_of([&] { tx::read_textgrid(dir.file("a.TextGrid"), "syllables"); });
  EXPECT_CONTAINS(msg, dir.file("a.TextGrid") + ": no tier named \"syllables\"");
  EXPECT_CONTAINS(msg, "\"words\" (IntervalTier), \"phones\" (IntervalTier), \"beats\" (TextTier)");
  const std::string point = error_of([&] { tx::read_textgrid(dir.file("a.TextGrid"), "beats"); });
  EXPECT_CONTAINS(point, "the tier \"beats\" is a TextTier, not an IntervalTier");
}

TEST(TextGridTier, WithoutATierNamedWordsTheOnlyIntervalTierIsRead) {
  TempDir dir;
  // One interval tier (and a point tier, which holds no words): it is the transcript.
  write_text(dir.file("one.TextGrid"), grid_of({{"ortho", "hello"}}, "beats"));
  const auto words = tx::read_textgrid(dir.file("one.TextGrid"));
  ASSERT_EQ(words.size(), 1u);
  EXPECT_EQ(words[0].text, "hello");
  EXPECT_EQ(words[0].start, 0.5);
  EXPECT_EQ(words[0].end, 1.25);
  // A tier named "words" (any case) wins over the other tiers.
  write_text(dir.file("w.TextGrid"), grid_of({{"phones", "HH"}, {"Words", "hi"}}));
  EXPECT_EQ(tx::read_textgrid(dir.file("w.TextGrid")).at(0).text, "hi");
  // Two interval tiers, neither a words tier: the reader cannot guess.
  write_text(dir.file("two.TextGrid"), grid_of({{"ortho", "hello"}, {"phones", "HH"}}));
  const std::string msg = error_of([&] { tx::read_textgrid(dir.file("two.TextGrid")); });
  EXPECT_CONTAINS(msg, "no tier named \"words\" and more than one interval tier");
  EXPECT_CONTAINS(msg, "\"ortho\" (IntervalTier), \"phones\" (IntervalTier)");
  EXPECT_CONTAINS(msg, "--tier NAME");
  write_text(dir.file("none.TextGrid"), grid_of({}, "beats"));
  EXPECT_CONTAINS(error_of([&] { tx::read_textgrid(dir.file("none.TextGrid")); }), "and no interval tier");
}

TEST(TextGridTier, ATierWithAnotherFormatIsAnError) {
  TempDir dir;
  write_text(dir.file("a.tsv"), "0\t1\thello\n");
  EXPECT_CONTAINS(error_of([&] { tx::read_transcript(dir.file("a.tsv"), tx::TranscriptFormat::Auto, "words"); }),
                  "a.tsv: a tier (\"words\") was given, but only a TextGrid transcript has tiers");
}

}  // namespace
