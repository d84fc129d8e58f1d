// Tests of text/keywords: normalisation, matching rules, frames, lexicon files, real transcripts.
#include <gtest/gtest.h>

#include <iostream>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"
#include "text/keywords.h"
#include "text/transcript.h"

namespace {

using gmg::testing::error_of;
using gmg::testing::TempDir;
using gmg::testing::write_text;
namespace tx = gmg::text;

tx::Lexicon lexicon_of(const std::vector<std::string>& entries) {
  tx::Lexicon lex;
  for (const auto& e : entries) lex.add(e);
  return lex;
}

TEST(TextKeywords, NormalizeWord) {
  EXPECT_EQ(tx::normalize_word("Don't!"), "don't");
  EXPECT_EQ(tx::normalize_word("well-known,"), "well-known");
  EXPECT_EQ(tx::normalize_word("  VERY, "), "very");
  EXPECT_EQ(tx::normalize_word("'quoted'"), "quoted");
  EXPECT_EQ(tx::normalize_word("-dash-"), "dash");
  EXPECT_EQ(tx::normalize_word("a--b"), "a-b");
  EXPECT_EQ(tx::normalize_word("Don\xE2\x80\x99t"), "don't");         // typographic apostrophe
  EXPECT_EQ(tx::normalize_word("\xE2\x80\x9CHi\xE2\x80\x9D"), "hi");  // curly quotes
  EXPECT_EQ(tx::normalize_word("Caf\xC3\xA9."), "caf\xC3\xA9");
  EXPECT_EQ(tx::normalize_word("#"), "");
  EXPECT_EQ(tx::normalize_word("..."), "");
  EXPECT_EQ(tx::normalize_word("A  Lot!"), "a lot");
}

// Bytes that are not well-formed UTF-8 are word characters taken one by one (engine/core/strings.h
// decode_utf8): an overlong form is such bytes, even when it spells a character that would be
// punctuation, a space or an apostrophe in its shortest form.
TEST(TextKeywords, NormalizeWordTakesMalformedUtf8AsWordBytes) {
  EXPECT_EQ(tx::normalize_word("a\xC2\xA0"
                               "b"),
            "a b");  // U+00A0, a no-break space: splits
  EXPECT_EQ(tx::normalize_word("a\xE0\x82\xA0"
                               "b"),
            "a\xE0\x82\xA0"
            "b");                                                                 // the same, overlong: kept
  EXPECT_EQ(tx::normalize_word("don\xE2\x80\x99t"), "don't");                     // U+2019: an apostrophe
  EXPECT_EQ(tx::normalize_word("don\xF0\x82\x80\x99t"), "don\xF0\x82\x80\x99t");  // overlong U+2019
  EXPECT_EQ(tx::normalize_word("\xE2\x80\x9Cx"), "x");                            // U+201C, a quote: stripped
  EXPECT_EQ(tx::normalize_word("\xF0\x82\x80\x9Cx"), "\xF0\x82\x80\x9Cx");        // overlong: kept
  EXPECT_EQ(tx::normalize_word("x\xED\xA0\x80"), "x\xED\xA0\x80");                // a surrogate: bytes kept
  EXPECT_EQ(tx::normalize_word("x\xE2\x80"), "x\xE2\x80");                        // cut short: bytes kept
  EXPECT_EQ(tx::normalize_word("\xE9t\xE9!"), "\xE9t\xE9");                       // Latin-1 bytes are word characters
  // A malformed byte between two words joins them as a word character would.
  EXPECT_EQ(tx::normalize_tokens("a\xC0\xA0"
                                 "b c"),
            (std::vector<std::string>{"a\xC0\xA0"
                                      "b",
                                      "c"}));
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
  std::vector<tx::Word> words = {{0, 0.1, "very"},   {0.2, 0.3, "big"}, {0.4, 0.5, "very"}, {0.6, 0.7, "nice"},
                                 {0.8, 0.9, "very"}, {1.0, 1.1, "#"},   {1.2, 1.3, "very"}};
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
  std::vector<tx::Word> hand = {
      {2.0, 2.1, "On"}, {2.1, 2.2, "the"}, {2.2, 2.5, "other"}, {2.5, 2.8, "hand,"}, {3.0, 3.2, "on"}};
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
  std::vector<tx::KeywordEvent> ev = {{1.0166, "a"}, {1.0167, "b"}, {1.02, "c"}, {2.0, "d"}, {-0.2, "e"}, {100.0, "f"}};
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
  write_text(dir.file("k.txt"), "\xEF\xBB\xBF# comment\r\nBig\r\n\r\n  on the Other hand  # phrase\r\nbig\r\n");
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

}  // namespace
