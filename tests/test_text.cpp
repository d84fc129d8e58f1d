// Tests of the text module: transcript readers (TSV, TextGrid, Google JSON) and keywords.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "tests/test_support.h"
#include "text/keywords.h"
#include "text/transcript.h"

using gmg::testing::TempDir;
using gmg::testing::write_text;
namespace tx = gmg::text;

namespace {

// Runs f, expects a gmg::Error, returns its message ("" and a failure when none is thrown).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const gmg::Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected gmg::Error, got another exception: " << e.what();
    return e.what();
  }
  ADD_FAILURE() << "expected gmg::Error, nothing was thrown";
  return "";
}

#define EXPECT_CONTAINS(haystack, needle)                                              \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos)                     \
      << "message: \"" << (haystack) << "\" should contain \"" << (needle) << "\""

std::vector<tx::Word> tsv_from(const TempDir& dir, const std::string& content,
                               const std::string& name = "t.tsv") {
  write_text(dir.file(name), content);
  return tx::read_tsv(dir.file(name));
}

// Encodes ASCII/UTF-8-free text as UTF-16 with a byte-order mark.
std::string to_utf16(const std::string& ascii, bool little_endian) {
  std::string out = little_endian ? std::string("\xFF\xFE", 2) : std::string("\xFE\xFF", 2);
  for (char c : ascii) {
    if (little_endian) {
      out += c;
      out += '\0';
    } else {
      out += '\0';
      out += c;
    }
  }
  return out;
}

const char* kLongTextGrid =
    "File type = \"ooTextFile\"\n"
    "Object class = \"TextGrid\"\n"
    "\n"
    "xmin = 0 \n"
    "xmax = 3.5 \n"
    "tiers? <exists> \n"
    "size = 2 \n"
    "item []: \n"
    "    item [1]:\n"
    "        class = \"IntervalTier\" \n"
    "        name = \"phones\" \n"
    "        xmin = 0 \n"
    "        xmax = 3.5 \n"
    "        intervals: size = 2 \n"
    "        intervals [1]:\n"
    "            xmin = 0 \n"
    "            xmax = 1 \n"
    "            text = \"\" \n"
    "        intervals [2]:\n"
    "            xmin = 1 \n"
    "            xmax = 3.5 \n"
    "            text = \"AH0\" \n"
    "    item [2]:\n"
    "        class = \"IntervalTier\" \n"
    "        name = \"words\" \n"
    "        xmin = 0 \n"
    "        xmax = 3.5 \n"
    "        intervals: size = 5 \n"
    "        intervals [1]:\n"
    "            xmin = 0 \n"
    "            xmax = 1 \n"
    "            text = \"\" \n"
    "        intervals [2]:\n"
    "            xmin = 1 \n"
    "            xmax = 1.5 \n"
    "            text = \"very\" \n"
    "        intervals [3]:\n"
    "            xmin = 1.5 \n"
    "            xmax = 2 \n"
    "            text = \"   \" \n"
    "        intervals [4]:\n"
    "            xmin = 2 \n"
    "            xmax = 2.25 \n"
    "            text = \"big\" \n"
    "        intervals [5]:\n"
    "            xmin = 2.25 \n"
    "            xmax = 3.5 \n"
    "            text = \"say \"\"hi\"\"\" \n";

std::string replace_once(std::string s, const std::string& from, const std::string& to) {
  std::size_t p = s.find(from);
  EXPECT_NE(p, std::string::npos) << "test bug: " << from << " not in the text";
  if (p != std::string::npos) s.replace(p, from.size(), to);
  return s;
}

tx::Lexicon lexicon_of(const std::vector<std::string>& entries) {
  tx::Lexicon lex;
  for (const auto& e : entries) lex.add(e);
  return lex;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// TSV

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
  auto words = tsv_from(dir, "\xEF\xBB\xBF" "0.1\t0.2\tHi\r\n\r\n   \r\n0.3\t0.6\t#\r\n0.7\t0.8\tthere\r\n");
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
  EXPECT_CONTAINS(msg, "line 1");
}

TEST(TextTsv, NanInfAndNegativeTimes) {
  TempDir dir;
  std::string msg = error_of([&] { tsv_from(dir, "nan\t1\ta\n"); });
  EXPECT_CONTAINS(msg, "line 1");
  EXPECT_CONTAINS(msg, "not a finite number");
  msg = error_of([&] { tsv_from(dir, "0\t1\ta\n1\tinf\tb\n"); });
  EXPECT_CONTAINS(msg, "line 2");
  EXPECT_CONTAINS(msg, "not a finite number");
  msg = error_of([&] { tsv_from(dir, "-0.5\t1\ta\n"); });
  EXPECT_CONTAINS(msg, "line 1");
  EXPECT_CONTAINS(msg, "negative");
}

TEST(TextTsv, TooFewFields) {
  TempDir dir;
  std::string msg = error_of([&] { tsv_from(dir, "0\t1\ta\n\n1\t2\n"); });
  EXPECT_CONTAINS(msg, "t.tsv: line 3");
  EXPECT_CONTAINS(msg, "2 field(s)");
}

TEST(TextTsv, MissingFileNamesIt) {
  TempDir dir;
  std::string msg = error_of([&] { tx::read_tsv(dir.file("nope.tsv")); });
  EXPECT_CONTAINS(msg, dir.file("nope.tsv"));
  EXPECT_CONTAINS(msg, "cannot open");
}

// ---------------------------------------------------------------------------------------------
// TextGrid

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
  EXPECT_CONTAINS(msg, "line 43");
  EXPECT_CONTAINS(msg, "not a number");

  write_text(dir.file("y.TextGrid"), replace_once(kLongTextGrid, "xmax = 2.25", "xmax = nan"));
  msg = error_of([&] { tx::read_textgrid(dir.file("y.TextGrid")); });
  EXPECT_CONTAINS(msg, "line 43");
  EXPECT_CONTAINS(msg, "not a finite number");

  write_text(dir.file("z.TextGrid"), replace_once(kLongTextGrid, "xmax = 2.25", "xmax = 1.75"));
  msg = error_of([&] { tx::read_textgrid(dir.file("z.TextGrid")); });
  EXPECT_CONTAINS(msg, "line 42");
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

// ---------------------------------------------------------------------------------------------
// Google JSON

TEST(TextJson, GoogleFormatWithDurationStrings) {
  TempDir dir;
  write_text(dir.file("g.json"), R"([
    {"alternatives": [{"transcript": "hello there", "confidence": 0.9,
      "words": [{"start_time": "1.500s", "end_time": "1.800s", "word": "hello"},
                {"start_time": "1.800s", "end_time": "2.100s", "word": "there"}]}]},
    {"alternatives": [{"transcript": "again",
      "words": [{"start_time": "0s", "end_time": "0.400s", "word": "First"}]},
                      {"words": [{"start_time": "9s", "end_time": "9.5s", "word": "ignored"}]}]}
  ])");
  auto words = tx::read_google_json(dir.file("g.json"));
  ASSERT_EQ(words.size(), 3u);
  EXPECT_EQ(words[0].text, "First");  // sorted by start
  EXPECT_DOUBLE_EQ(words[0].start, 0.0);
  EXPECT_DOUBLE_EQ(words[0].end, 0.4);
  EXPECT_EQ(words[1].text, "hello");
  EXPECT_DOUBLE_EQ(words[1].start, 1.5);
  EXPECT_DOUBLE_EQ(words[1].end, 1.8);
  EXPECT_EQ(words[2].text, "there");
  EXPECT_DOUBLE_EQ(words[2].end, 2.1);
}

TEST(TextJson, NumbersObjectsAndResultsObject) {
  TempDir dir;
  write_text(dir.file("n.json"), R"({"results": [
    {"alternatives": [{"words": [
      {"start_time": 0.25, "end_time": 0.5, "word": "a"},
      {"startTime": {"seconds": "1", "nanos": 500000000}, "endTime": {"seconds": 2}, "word": "b"}]}]},
    {"alternatives": []}, {}
  ]})");
  auto words = tx::read_google_json(dir.file("n.json"));
  ASSERT_EQ(words.size(), 2u);
  EXPECT_DOUBLE_EQ(words[0].start, 0.25);
  EXPECT_DOUBLE_EQ(words[0].end, 0.5);
  EXPECT_DOUBLE_EQ(words[1].start, 1.5);
  EXPECT_DOUBLE_EQ(words[1].end, 2.0);
  EXPECT_EQ(words[1].text, "b");
}

TEST(TextJson, MalformedJsonNamesFileAndByte) {
  TempDir dir;
  write_text(dir.file("bad.json"), R"([{"alternatives": [{"words": [}]}])");
  std::string msg = error_of([&] { tx::read_google_json(dir.file("bad.json")); });
  EXPECT_CONTAINS(msg, dir.file("bad.json"));
  EXPECT_CONTAINS(msg, "byte 31");
  EXPECT_CONTAINS(msg, "invalid JSON");
}

TEST(TextJson, MissingFieldsAndBadTimes) {
  TempDir dir;
  write_text(dir.file("m.json"),
             R"([{"alternatives": [{"words": [{"start_time": "1s", "word": "x"}]}]}])");
  std::string msg = error_of([&] { tx::read_google_json(dir.file("m.json")); });
  EXPECT_CONTAINS(msg, "m.json");
  EXPECT_CONTAINS(msg, "[0].alternatives[0].words[0]");
  EXPECT_CONTAINS(msg, "missing \"end_time\"");

  write_text(dir.file("t.json"),
             R"([{"alternatives": [{"words": [{"start_time": "1.2xs", "end_time": "2s", "word": "x"}]}]}])");
  msg = error_of([&] { tx::read_google_json(dir.file("t.json")); });
  EXPECT_CONTAINS(msg, "t.json");
  EXPECT_CONTAINS(msg, "bad time \"1.2xs\"");

  write_text(dir.file("o.json"), R"({"foo": 1})");
  msg = error_of([&] { tx::read_google_json(dir.file("o.json")); });
  EXPECT_CONTAINS(msg, "o.json");
  EXPECT_CONTAINS(msg, "results");
}

// ---------------------------------------------------------------------------------------------
// Format selection, fitting the audio

TEST(TextFormat, ParseNames) {
  EXPECT_EQ(tx::parse_transcript_format("auto"), tx::TranscriptFormat::Auto);
  EXPECT_EQ(tx::parse_transcript_format("tsv"), tx::TranscriptFormat::Tsv);
  EXPECT_EQ(tx::parse_transcript_format("TextGrid"), tx::TranscriptFormat::TextGrid);
  EXPECT_EQ(tx::parse_transcript_format("json"), tx::TranscriptFormat::Json);
  std::string msg = error_of([] { tx::parse_transcript_format("srt"); });
  EXPECT_CONTAINS(msg, "srt");
  EXPECT_CONTAINS(msg, "textgrid");
}

TEST(TextFormat, ByExtensionAndExplicit) {
  TempDir dir;
  write_text(dir.file("a.tsv"), "0\t1\ttsv\n");
  write_text(dir.file("a.txt"), "0\t1\ttxt\n");
  write_text(dir.file("a.TextGrid"), kLongTextGrid);
  write_text(dir.file("b.textgrid"), kLongTextGrid);
  write_text(dir.file("a.json"), R"([{"alternatives":[{"words":[{"start_time":"0s","end_time":"1s","word":"json"}]}]}])");
  EXPECT_EQ(tx::read_transcript(dir.file("a.tsv")).at(0).text, "tsv");
  EXPECT_EQ(tx::read_transcript(dir.file("a.txt")).at(0).text, "txt");
  EXPECT_EQ(tx::read_transcript(dir.file("a.TextGrid")).at(0).text, "very");
  EXPECT_EQ(tx::read_transcript(dir.file("b.textgrid")).at(0).text, "very");
  EXPECT_EQ(tx::read_transcript(dir.file("a.json")).at(0).text, "json");

  write_text(dir.file("words.dat"), "0\t1\tdat\n");
  write_text(dir.file("grid.dat"), kLongTextGrid);
  write_text(dir.file("google.dat"), R"([{"alternatives":[{"words":[{"start_time":"0s","end_time":"1s","word":"g"}]}]}])");
  EXPECT_EQ(tx::read_transcript(dir.file("words.dat"), tx::TranscriptFormat::Tsv).at(0).text, "dat");
  EXPECT_EQ(tx::read_transcript(dir.file("grid.dat"), tx::TranscriptFormat::TextGrid).size(), 3u);
  EXPECT_EQ(tx::read_transcript(dir.file("google.dat"), tx::TranscriptFormat::Json).at(0).text, "g");
  // The explicit format wins over the extension.
  EXPECT_THROW(tx::read_transcript(dir.file("a.tsv"), tx::TranscriptFormat::Json), gmg::Error);
}

TEST(TextFormat, UnknownExtensionSuggestsOption) {
  TempDir dir;
  write_text(dir.file("words.dat"), "0\t1\tdat\n");
  std::string msg = error_of([&] { tx::read_transcript(dir.file("words.dat")); });
  EXPECT_CONTAINS(msg, "words.dat");
  EXPECT_CONTAINS(msg, "--transcript-format");
}

TEST(TextFormat, MissingFileThroughReadTranscript) {
  TempDir dir;
  std::string msg = error_of([&] { tx::read_transcript(dir.file("gone.TextGrid")); });
  EXPECT_CONTAINS(msg, "gone.TextGrid");
}

TEST(TextFits, PastTheEndNamesFile) {
  std::vector<tx::Word> words = {{0.0, 1.0, "a"}, {9.0, 10.04, "b"}};
  EXPECT_NO_THROW(tx::check_transcript_fits(words, 10.0, "t.tsv"));
  EXPECT_NO_THROW(tx::check_transcript_fits({}, 0.0, "t.tsv"));
  std::string msg = error_of([&] { tx::check_transcript_fits(words, 9.9, "some/t.tsv"); });
  EXPECT_CONTAINS(msg, "some/t.tsv");
  EXPECT_CONTAINS(msg, "\"b\"");
  EXPECT_THROW(tx::check_transcript_fits(words, 10.0, "t.tsv", 0.0), gmg::Error);
}

// ---------------------------------------------------------------------------------------------
// Keywords

TEST(TextKeywords, NormalizeWord) {
  EXPECT_EQ(tx::normalize_word("Don't!"), "don't");
  EXPECT_EQ(tx::normalize_word("well-known,"), "well-known");
  EXPECT_EQ(tx::normalize_word("  VERY, "), "very");
  EXPECT_EQ(tx::normalize_word("'quoted'"), "quoted");
  EXPECT_EQ(tx::normalize_word("-dash-"), "dash");
  EXPECT_EQ(tx::normalize_word("a--b"), "a-b");
  EXPECT_EQ(tx::normalize_word("Don\xE2\x80\x99t"), "don't");  // typographic apostrophe
  EXPECT_EQ(tx::normalize_word("\xE2\x80\x9CHi\xE2\x80\x9D"), "hi");  // curly quotes
  EXPECT_EQ(tx::normalize_word("Caf\xC3\xA9."), "caf\xC3\xA9");
  EXPECT_EQ(tx::normalize_word("#"), "");
  EXPECT_EQ(tx::normalize_word("..."), "");
  EXPECT_EQ(tx::normalize_word("A  Lot!"), "a lot");
}

TEST(TextKeywords, RunOfIdenticalKeywordsMarksFirst) {
  const auto lex = lexicon_of({"very", "big"});
  std::vector<tx::Word> words = {{1.0, 1.2, "very"}, {1.3, 1.5, "very"}, {1.6, 2.0, "big"}};
  auto ev = tx::detect_keywords(words, lex);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].keyword, "very");
  EXPECT_DOUBLE_EQ(ev[0].time, 1.0);
  EXPECT_EQ(ev[1].keyword, "big");
  EXPECT_DOUBLE_EQ(ev[1].time, 1.6);

  // Case and punctuation do not matter, and punctuation does not break the run.
  std::vector<tx::Word> shouted = {{1.0, 1.2, "Very,"}, {1.3, 1.5, "VERY"}, {1.6, 2.0, "big!"}};
  auto ev2 = tx::detect_keywords(shouted, lex);
  ASSERT_EQ(ev2.size(), 2u);
  EXPECT_EQ(ev2[0].keyword, "very");
  EXPECT_DOUBLE_EQ(ev2[0].time, 1.0);
  EXPECT_EQ(ev2[1].keyword, "big");
  EXPECT_DOUBLE_EQ(ev2[1].time, 1.6);
}

TEST(TextKeywords, OtherWordBreaksRunAndNonKeywordsIgnored) {
  const auto lex = lexicon_of({"very", "big"});
  std::vector<tx::Word> words = {{0, 0.1, "very"}, {0.2, 0.3, "big"}, {0.4, 0.5, "very"},
                                 {0.6, 0.7, "nice"}, {0.8, 0.9, "very"}, {1.0, 1.1, "#"},
                                 {1.2, 1.3, "very"}};
  auto ev = tx::detect_keywords(words, lex);
  ASSERT_EQ(ev.size(), 4u);
  EXPECT_DOUBLE_EQ(ev[0].time, 0.0);
  EXPECT_DOUBLE_EQ(ev[1].time, 0.2);
  EXPECT_DOUBLE_EQ(ev[2].time, 0.4);
  EXPECT_DOUBLE_EQ(ev[3].time, 0.8);  // laughter between the last two "very" is not a word
}

TEST(TextKeywords, PhraseOverWordsAndInsideOneTsvWord) {
  const auto lex = lexicon_of({"a lot", "lot", "big"});
  std::vector<tx::Word> two = {{0.5, 0.6, "A"}, {0.6, 0.9, "lot."}, {1.0, 1.2, "big"}};
  auto ev = tx::detect_keywords(two, lex);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].keyword, "a lot");  // longest match wins over "lot"
  EXPECT_DOUBLE_EQ(ev[0].time, 0.5);
  EXPECT_EQ(ev[1].keyword, "big");

  TempDir dir;
  write_text(dir.file("p.tsv"), "0.5\t0.9\ta lot\n1.0\t1.2\tof fun\n");
  auto ev2 = tx::detect_keywords(tx::read_tsv(dir.file("p.tsv")), lex);
  ASSERT_EQ(ev2.size(), 1u);
  EXPECT_EQ(ev2[0].keyword, "a lot");
  EXPECT_DOUBLE_EQ(ev2[0].time, 0.5);

  // Longest first even when the shorter entry comes first in the lexicon and shares the first token.
  const auto overlapping = lexicon_of({"on", "other", "on the other hand"});
  std::vector<tx::Word> hand = {{2.0, 2.1, "On"}, {2.1, 2.2, "the"}, {2.2, 2.5, "other"},
                                {2.5, 2.8, "hand,"}, {3.0, 3.2, "on"}};
  auto ev3 = tx::detect_keywords(hand, overlapping);
  ASSERT_EQ(ev3.size(), 2u);
  EXPECT_EQ(ev3[0].keyword, "on the other hand");
  EXPECT_DOUBLE_EQ(ev3[0].time, 2.0);
  EXPECT_EQ(ev3[1].keyword, "on");
  EXPECT_DOUBLE_EQ(ev3[1].time, 3.0);

  // "a" alone is not a keyword.
  std::vector<tx::Word> lone = {{0, 0.1, "a"}, {0.2, 0.3, "dog"}};
  EXPECT_TRUE(tx::detect_keywords(lone, lex).empty());
}

TEST(TextKeywords, KeywordFramesRoundDropOutsideAndDedupe) {
  std::vector<tx::KeywordEvent> ev = {{1.0166, "a"}, {1.0167, "b"}, {1.02, "c"},
                                      {2.0, "d"},    {-0.2, "e"},   {100.0, "f"}};
  auto frames = tx::keyword_frames(ev, 30.0, 1000);
  // 1.0166 * 30 = 30.498 -> 30; 1.0167 * 30 = 30.501 -> 31; 1.02 * 30 = 30.6 -> 31 (dropped).
  // -0.2 s and 100 s (frame 3000) fall outside [0, 1000): dropped.
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].frame, 30);
  EXPECT_EQ(frames[0].keyword, "a");
  EXPECT_EQ(frames[1].frame, 31);
  EXPECT_EQ(frames[1].keyword, "b");
  EXPECT_EQ(frames[2].frame, 60);
  EXPECT_EQ(frames[2].keyword, "d");

  EXPECT_TRUE(tx::keyword_frames(ev, 30.0, 0).empty());
  EXPECT_THROW(tx::keyword_frames(ev, 0.0, 10), gmg::Error);
}

TEST(TextKeywords, LoadLexiconFile) {
  TempDir dir;
  write_text(dir.file("k.txt"),
             "\xEF\xBB\xBF# comment\r\nBig\r\n\r\n  on the Other hand  # phrase\r\nbig\r\n");
  auto lex = tx::load_lexicon(dir.file("k.txt"));
  EXPECT_EQ(lex.size(), 2u);
  EXPECT_TRUE(lex.contains("big"));
  EXPECT_TRUE(lex.contains("On the other hand"));
  EXPECT_FALSE(lex.contains("other"));
  ASSERT_EQ(lex.phrases.at(1).size(), 4u);

  write_text(dir.file("empty.txt"), "# nothing\n\n");
  std::string msg = error_of([&] { tx::load_lexicon(dir.file("empty.txt")); });
  EXPECT_CONTAINS(msg, "empty.txt");
  msg = error_of([&] { tx::load_lexicon(dir.file("missing.txt")); });
  EXPECT_CONTAINS(msg, "missing.txt");
  write_text(dir.file("punct.txt"), "big\n!!!\n");
  msg = error_of([&] { tx::load_lexicon(dir.file("punct.txt")); });
  EXPECT_CONTAINS(msg, "punct.txt: line 2");
}

TEST(TextKeywords, DefaultLexiconLoads) {
  auto lex = tx::default_lexicon();
  EXPECT_GE(lex.size(), 150u);
  EXPECT_LE(lex.size(), 260u);
  for (const char* w : {"big", "not", "this", "very", "don't", "a lot", "on the other hand"})
    EXPECT_TRUE(lex.contains(w)) << w;
  for (const char* w : {"the", "a", "and", "is", "to", "of"}) EXPECT_FALSE(lex.contains(w)) << w;
}

// ---------------------------------------------------------------------------------------------
// Real data

TEST(TextRealData, Beat2ScottTextGrids) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string dir = gmg::testing::shared_data_dir() + "/beat2_scott/";
  const auto lex = tx::default_lexicon();
  for (const char* name : {"2_scott_0_1_1", "2_scott_0_2_2", "2_scott_0_3_3"}) {
    SCOPED_TRACE(name);
    const std::string path = dir + name + ".TextGrid";
    auto words = tx::read_transcript(path);
    EXPECT_GT(words.size(), 100u);
    for (std::size_t i = 0; i < words.size(); ++i) {
      EXPECT_LE(words[i].start, words[i].end);
      EXPECT_FALSE(words[i].text.empty());
      if (i > 0) {
        EXPECT_LE(words[i - 1].start, words[i].start);
        EXPECT_LE(words[i - 1].end, words[i].start + 1e-9);  // aligned words do not overlap
      }
    }
    auto ev = tx::detect_keywords(words, lex);
    std::cout << "[ info ] " << name << ": " << words.size() << " words, " << ev.size()
              << " keyword events, last word ends at " << words.back().end << " s\n";
    EXPECT_GE(ev.size(), words.size() / 20);  // plausible: several keywords a minute...
    EXPECT_LE(ev.size(), words.size() / 2);   // ...but far from every word
    for (std::size_t i = 1; i < ev.size(); ++i) EXPECT_LE(ev[i - 1].time, ev[i].time);
    if (std::string(name) == "2_scott_0_1_1") {
      EXPECT_NEAR(words.back().end, 62.4, 0.05);
      EXPECT_EQ(words.front().text, "the");
      EXPECT_DOUBLE_EQ(words.front().start, 1.42);
      EXPECT_NO_THROW(tx::check_transcript_fits(words, 64.1, path));
      EXPECT_THROW(tx::check_transcript_fits(words, 60.0, path), gmg::Error);
    }
  }
}
