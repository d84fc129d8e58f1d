// Tests of text/google_json: Google speech-to-text JSON transcripts.
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
  EXPECT_EQ(msg.rfind(dir.file("bad.json") + ": byte 31: invalid JSON (", 0), 0u) << msg;
}

TEST(TextJson, NumberBeyondDoubleNamesFileAndByte) {
  // Before the core JSON reader this escaped as nlohmann's own out_of_range, with no file in it.
  // The 1e309 takes bytes 46 to 50 of the text below.
  TempDir dir;
  const std::string path = dir.file("huge.json");
  write_text(path, R"([{"alternatives": [{"words": [{"start_time": 1e309, "end_time": 1, "word": "x"}]}]}])");
  EXPECT_EQ(error_of([&] { tx::read_google_json(path); }),
            path + ": byte 50: invalid JSON (the number 1e309 is out of range for a double)");
}

TEST(TextJson, Utf16FileIsDecodedFirst) {
  // Windows tools export JSON as UTF-16LE with a byte-order mark.
  const std::string text = R"([{"alternatives": [{"words": [{"start_time": "1s", "end_time": "2s", "word": "hi"}]}]}])";
  std::string utf16 = "\xFF\xFE";
  for (char c : text) {
    utf16 += c;
    utf16 += '\0';
  }
  TempDir dir;
  write_text(dir.file("w.json"), utf16);
  const auto words = tx::read_google_json(dir.file("w.json"));
  ASSERT_EQ(words.size(), 1u);
  EXPECT_EQ(words[0].text, "hi");
  EXPECT_DOUBLE_EQ(words[0].start, 1.0);
  EXPECT_DOUBLE_EQ(words[0].end, 2.0);
}

TEST(TextJson, MissingFileUsesTheReaderWording) {
  TempDir dir;
  EXPECT_EQ(error_of([&] { tx::read_google_json(dir.file("none.json")); }),
            dir.file("none.json") + ": cannot open (No such file or directory)");
}

TEST(TextJson, MissingFieldsAndBadTimes) {
  TempDir dir;
  write_text(dir.file("m.json"), R"([{"alternatives": [{"words": [{"start_time": "1s", "word": "x"}]}]}])");
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

// The word checks the Google reader shares with the Whisper one (text/json_words.h): the word's
// text, and its times in order, each error at the word's JSON location.
TEST(TextJson, WordTextAndOrderAreChecked) {
  TempDir dir;
  auto error_for = [&](const std::string& word) {
    write_text(dir.file("w.json"), R"([{"alternatives": [{"words": [)" + word + "]}]}]");
    return error_of([&] { tx::read_google_json(dir.file("w.json")); });
  };
  const std::string at = dir.file("w.json") + ": [0].alternatives[0].words[0]";
  EXPECT_EQ(error_for(R"({"start_time": "1s", "end_time": "2s"})"), at + ": missing \"word\"");
  EXPECT_EQ(error_for(R"({"start_time": "1s", "end_time": "2s", "word": 3})"), at + ".word: expected a string");
  EXPECT_EQ(error_for(R"({"start_time": "3s", "end_time": "2.5s", "word": " x "})"),
            at + ": word \"x\" ends (2.5 s) before it starts (3 s)");
  EXPECT_EQ(error_for("7"), at + ": expected a word object");
}

}  // namespace
