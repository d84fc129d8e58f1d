// Tests of text/whisper_json: Whisper and WhisperX JSON word timings, and the JSON front door
// that tells them from Google speech JSON.
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

// What `whisper audio.wav --word_timestamps True --output_format json` writes (abridged): words
// start with a space and carry their punctuation.
const char* const kWhisper = R"({
  "text": " Hello there. Big news.",
  "segments": [
    {"id": 0, "seek": 0, "start": 0.0, "end": 1.6, "text": " Hello there.", "tokens": [50364, 2425],
     "temperature": 0.0, "avg_logprob": -0.2, "compression_ratio": 0.8, "no_speech_prob": 0.01,
     "words": [{"word": " Hello", "start": 0.12, "end": 0.5, "probability": 0.93},
               {"word": " there.", "start": 0.5, "end": 1.02, "probability": 0.88}]},
    {"id": 1, "seek": 0, "start": 2.0, "end": 3.0, "text": " Big news.",
     "words": [{"word": " Big", "start": 2.0, "end": 2.31, "probability": 0.9},
               {"word": " news.", "start": 2.31, "end": 2.9, "probability": 0.95}]}
  ],
  "language": "en"
})";

TEST(WhisperJson, WhisperSegmentWordsAreReadTrimmedInOrder) {
  TempDir dir;
  write_text(dir.file("w.json"), kWhisper);
  for (const auto& words : {tx::read_whisper_json(dir.file("w.json")), tx::read_transcript(dir.file("w.json"))}) {
    ASSERT_EQ(words.size(), 4u);
    EXPECT_EQ(words[0].text, "Hello");
    EXPECT_EQ(words[0].start, 0.12);
    EXPECT_EQ(words[0].end, 0.5);
    EXPECT_EQ(words[1].text, "there.");
    EXPECT_EQ(words[3].text, "news.");
    EXPECT_EQ(words[3].start, 2.31);
    EXPECT_EQ(words[3].end, 2.9);
  }
}

TEST(WhisperJson, WhisperXUntimedWordsTakeTheGapBetweenTheirNeighbours) {
  // WhisperX: "score" instead of "probability", and no times for "1990" (digits cannot be aligned)
  // nor for the segment-final "5": the first takes the gap 1.0..1.4 between "in" and "we", the
  // second runs from the previous word's end (2.2) to its segment's end (2.5).
  TempDir dir;
  write_text(dir.file("x.json"), R"({
    "segments": [
      {"start": 0.5, "end": 2.5, "text": " In 1990 we had 5",
       "words": [{"word": "In", "start": 0.5, "end": 1.0, "score": 0.9},
                 {"word": "1990"},
                 {"word": "we", "start": 1.4, "end": 1.6, "score": 0.8},
                 {"word": "had", "start": 1.7, "end": 2.2, "score": 0.8},
                 {"word": "5"}]}
    ],
    "word_segments": [{"word": "ignored", "start": 9.0, "end": 9.5}]
  })");
  const auto words = tx::read_transcript(dir.file("x.json"));
  ASSERT_EQ(words.size(), 5u);  // segments[].words[] wins over word_segments, which repeats it
  EXPECT_EQ(words[1].text, "1990");
  EXPECT_EQ(words[1].start, 1.0);
  EXPECT_EQ(words[1].end, 1.4);
  EXPECT_EQ(words[4].text, "5");
  EXPECT_EQ(words[4].start, 2.2);
  EXPECT_EQ(words[4].end, 2.5);
}

TEST(WhisperJson, WhisperXWordSegmentsAloneAreRead) {
  TempDir dir;
  write_text(dir.file("ws.json"), R"({"word_segments": [
      {"word": "two", "start": 1.5, "end": 1.75, "score": 0.7},
      {"word": "3"},
      {"word": "one", "start": 0.25, "end": 0.5, "score": 0.9}]})");
  const auto words = tx::read_transcript(dir.file("ws.json"));
  ASSERT_EQ(words.size(), 3u);
  // Sorted by start; "3" sits between its neighbours in the file: from 1.75 to 0.25 would be
  // backwards, so it is the point 1.75.
  EXPECT_EQ(words[0].text, "one");
  EXPECT_EQ(words[1].text, "two");
  EXPECT_EQ(words[2].text, "3");
  EXPECT_EQ(words[2].start, 1.75);
  EXPECT_EQ(words[2].end, 1.75);
}

TEST(WhisperJson, SegmentsWithoutWordTimingsSayHowToGetThem) {
  TempDir dir;
  write_text(dir.file("s.json"),
             R"({"text": " Hi.", "segments": [{"id": 0, "start": 0.0, "end": 1.0, "text": " Hi."}]})");
  const std::string msg = error_of([&] { tx::read_transcript(dir.file("s.json")); });
  EXPECT_CONTAINS(msg, dir.file("s.json") + ": Whisper JSON without word timings");
  EXPECT_CONTAINS(msg, "--word_timestamps True");
  EXPECT_CONTAINS(msg, "WhisperX");
  // No segments at all: a silent clip, zero words.
  write_text(dir.file("e.json"), R"({"text": "", "segments": [], "language": "en"})");
  EXPECT_TRUE(tx::read_transcript(dir.file("e.json")).empty());
}

TEST(WhisperJson, MalformedWordsNameTheJsonLocation) {
  TempDir dir;
  auto error_for = [&](const std::string& words) {
    write_text(
        dir.file("m.json"),
        R"({"segments": [{"start": 0, "end": 9, "words": [{"word": "ok", "start": 0, "end": 1},)" + words + "]}]}");
    return error_of([&] { tx::read_transcript(dir.file("m.json")); });
  };
  EXPECT_CONTAINS(error_for(R"({"start": 1, "end": 2})"), "m.json: segments[0].words[1]: missing \"word\"");
  EXPECT_CONTAINS(error_for(R"({"word": "x", "start": "1.5", "end": 2})"),
                  "segments[0].words[1].start: expected a number of seconds, found \"1.5\"");
  EXPECT_CONTAINS(error_for(R"({"word": "x", "start": 3, "end": 2})"), "word \"x\" ends (2 s) before it starts (3 s)");
  EXPECT_CONTAINS(error_for(R"({"word": "x", "start": -1, "end": 2})"), "negative time -1");
  EXPECT_CONTAINS(error_for(R"({"word": "x", "start": 1})"), "segments[0].words[1]: has \"start\" but no \"end\"");
  EXPECT_CONTAINS(error_for(R"(7)"), "segments[0].words[1]: expected a word object");
  write_text(dir.file("t.json"), R"({"segments": [{"words": [{"word": "x", "start": 1, "end": 2}]}, 5]})");
  EXPECT_CONTAINS(error_of([&] { tx::read_transcript(dir.file("t.json")); }), "segments[1]: expected a segment object");
}

TEST(WhisperJson, GoogleJsonStillGoesToTheGoogleReader) {
  TempDir dir;
  write_text(dir.file("g.json"),
             R"([{"alternatives": [{"words": [{"start_time": "1.5s", "end_time": "1.8s", "word": "hello"}]}]}])");
  const auto words = tx::read_transcript(dir.file("g.json"));
  ASSERT_EQ(words.size(), 1u);
  EXPECT_EQ(words[0].start, 1.5);
  EXPECT_CONTAINS(error_of([&] { tx::read_whisper_json(dir.file("g.json")); }), "not a Whisper JSON");
}

}  // namespace
