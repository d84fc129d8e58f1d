// Tests of text/transcript: format names, choice by extension, the fit to the audio.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
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
  write_text(dir.file("a.json"),
             R"([{"alternatives":[{"words":[{"start_time":"0s","end_time":"1s","word":"json"}]}]}])");
  EXPECT_EQ(tx::read_transcript(dir.file("a.tsv")).at(0).text, "tsv");
  EXPECT_EQ(tx::read_transcript(dir.file("a.txt")).at(0).text, "txt");
  EXPECT_EQ(tx::read_transcript(dir.file("a.TextGrid")).at(0).text, "very");
  EXPECT_EQ(tx::read_transcript(dir.file("b.textgrid")).at(0).text, "very");
  EXPECT_EQ(tx::read_transcript(dir.file("a.json")).at(0).text, "json");

  write_text(dir.file("words.dat"), "0\t1\tdat\n");
  write_text(dir.file("grid.dat"), kLongTextGrid);
  write_text(dir.file("google.dat"),
             R"([{"alternatives":[{"words":[{"start_time":"0s","end_time":"1s","word":"g"}]}]}])");
  EXPECT_EQ(tx::read_transcript(dir.file("words.dat"), tx::TranscriptFormat::Tsv).at(0).text, "dat");
  EXPECT_EQ(tx::read_transcript(dir.file("grid.dat"), tx::TranscriptFormat::TextGrid).size(), 3u);
  EXPECT_EQ(tx::read_transcript(dir.file("google.dat"), tx::TranscriptFormat::Json).at(0).text, "g");
  // The explicit format wins over the extension: "0\t1\ttsv" read as JSON is the number 0 and
  // then a second value, the 1 at byte 3, where the input should end.
  const std::string msg = error_of([&] { tx::read_transcript(dir.file("a.tsv"), tx::TranscriptFormat::Json); });
  EXPECT_EQ(msg.rfind(dir.file("a.tsv") + ": byte 3: invalid JSON (", 0), 0u) << msg;
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
  EXPECT_EQ(error_of([&] { tx::read_transcript(dir.file("gone.TextGrid")); }),
            dir.file("gone.TextGrid") + ": cannot open (No such file or directory)");
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

// The readers of bytes in memory (the fuzz harnesses use them) read what the file readers read
// and name the label they are given.
TEST(TextFormat, ParsersOfBytesInMemoryNameTheirLabel) {
  EXPECT_EQ(tx::parse_tsv("0\t1\tword\n", "mem.tsv").at(0).text, "word");
  EXPECT_EQ(tx::parse_textgrid(gmg::testing::to_utf16(kLongTextGrid, true), "mem.TextGrid").size(),
            tx::parse_textgrid(kLongTextGrid, "mem.TextGrid").size());
  EXPECT_EQ(tx::parse_google_json(R"([{"alternatives":[{"words":[{"start_time":"0s","end_time":"1s","word":"x"}]}]}])",
                                  "mem.json")
                .at(0)
                .text,
            "x");
  EXPECT_EQ(error_of([] { tx::parse_tsv("0\tone\tword\n", "mem.tsv"); }).rfind("mem.tsv: line 1: ", 0), 0u);
  EXPECT_EQ(error_of([] { tx::parse_textgrid("nothing", "mem.TextGrid"); }).rfind("mem.TextGrid", 0), 0u);
  EXPECT_EQ(error_of([] { tx::parse_google_json("[1e309]", "mem.json"); }),
            "mem.json: byte 6: invalid JSON (the number 1e309 is out of range for a double)");
}

TEST(TextFormat, FolderAsTranscriptIsAnError) {
  TempDir dir;
  std::filesystem::create_directories(dir.file("words.tsv"));
  EXPECT_EQ(error_of([&] { tx::read_transcript(dir.file("words.tsv")); }),
            dir.file("words.tsv") + ": is a folder, not a file");
}

}  // namespace
