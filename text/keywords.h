// Keywords: words and phrases that usually carry a semantic gesture (SPEC "Keyword nodes").
//
// Matching rules (the contract of detect_keywords):
// - Tokens: each Word's text is split on whitespace (a GENEA TSV "word" may hold several
//   words) and every token is normalised with normalize_word. Tokens that normalise to the
//   empty string (pure punctuation, the laughter mark "#") are dropped before matching: they
//   neither match nor interrupt a phrase or a run.
// - At each token position the longest lexicon phrase that matches the following tokens wins
//   (phrases may span several Words); matching then continues after the phrase.
// - "Consecutive" means adjacent in that token sequence: two matches of the same keyword form a
//   run when the second starts right where the first ends, with no other token in between.
//   Punctuation does not separate ("very, very" is a run), any other word does ("very big
//   very" gives three events). A run yields one event, for its first occurrence.
// - The time of an event is the start of the Word that holds the first token of the match
//   (of the run's first match). Tokens inside one multi-word Word share that Word's start.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "text/transcript.h"

namespace gmg::text {

// Lower-cases ASCII letters, maps typographic apostrophes (U+2018, U+2019) to "'", strips
// punctuation except apostrophes and hyphens between two word characters ("Don't!" -> "don't",
// "well-known," -> "well-known", "'quoted'" -> "quoted"), and trims whitespace. Word characters
// are ASCII letters and digits and any non-ASCII UTF-8 character other than typographic
// punctuation (curly quotes, dashes, ellipsis, non-breaking space), which is stripped too.
// A run of several inner apostrophes/hyphens is kept as its first one ("a--b" -> "a-b").
// Returns "" when nothing is left ("#", "...").
std::string normalize_word(const std::string& w);

// Splits text on whitespace and normalises every piece; empty results are dropped.
std::vector<std::string> normalize_tokens(const std::string& text);

struct Lexicon {
  // Each entry is a phrase of normalised, non-empty tokens (a single word is a 1-token phrase).
  // No duplicates, no empty phrases (when filled through add / load_lexicon).
  std::vector<std::vector<std::string>> phrases;

  // Adds a word or phrase (normalised with normalize_tokens); ignores duplicates.
  // Returns false when the phrase normalises to nothing (nothing is added) or is a duplicate.
  bool add(const std::string& phrase);

  // True when `phrase` (normalised like add does) is in the lexicon.
  bool contains(const std::string& phrase) const;

  std::size_t size() const { return phrases.size(); }
  bool empty() const { return phrases.empty(); }
};

// One word or phrase per line; '#' starts a comment (to the end of the line); blank lines are
// ignored; duplicates are merged. UTF-8 (BOM allowed), UTF-16 with BOM, LF or CRLF.
// gmg::Error naming the file when it is missing/unreadable, when a line normalises to nothing
// (with the line number), or when it holds no entry at all.
Lexicon load_lexicon(const std::string& path);

// The same from text already in memory (UTF-8); `path` names it in errors.
Lexicon parse_lexicon(const std::string& text, const std::string& path);

// The lexicon shipped with the project (assets/keywords.txt), compiled into the binary so that
// an installed or moved gmg needs no source tree.
Lexicon default_lexicon();

struct KeywordEvent {
  double time = 0;      // seconds: start of the Word holding the first token of the run's first match
  std::string keyword;  // the matched lexicon phrase, tokens joined by one space ("a lot")
};

// Finds the keywords of `words` (assumed sorted by start, as the readers return them) under the
// rules at the top of this file. Events come in transcript order (non-decreasing time).
std::vector<KeywordEvent> detect_keywords(const std::vector<Word>& words, const Lexicon& lexicon);

struct KeywordFrame {
  int frame = 0;        // motion frame: round(time * fps), in [0, num_frames)
  std::string keyword;  // the event's keyword
};

// Converts events to motion frames. Events outside [0, num_frames) are dropped (a transcript
// may outlast the motion). When several events fall in the same frame only the first (in the
// order given) is kept. The result is sorted by frame. num_frames <= 0 gives no frames;
// a non-positive or non-finite fps is a gmg::Error.
std::vector<KeywordFrame> keyword_frames(const std::vector<KeywordEvent>& ev, double fps, int num_frames);

}  // namespace gmg::text
