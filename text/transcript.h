// Word-level transcripts: the formats seen in co-speech gesture datasets and speech recognisers.
//
//   GENEA 2022/2023 TSV      start<TAB>end<TAB>word         (read_tsv)
//   BEAT/BEAT2 Praat TextGrid, tier "words"                 (read_textgrid)
//   GENEA 2020 Google speech JSON, alternatives[0].words[]   (read_google_json)
//   Whisper / WhisperX JSON, segments[].words[] or word_segments[]  (read_whisper_json)
//
// Contract shared by every reader:
// - the result is sorted by start time (stable: words with equal starts keep file order);
// - every word has finite times with 0 <= start <= end (seconds from the start of the audio);
// - zero words is a valid result (a silent clip), but a missing or unreadable file is an error;
// - every problem throws gmg::Error whose message names the file and, where there is one, the
//   line ("t.tsv: line 3: ...") or byte offset ("t.json: byte 17: ...").
// Text is UTF-8 in the result; files may be UTF-8 (with or without a byte-order mark) or
// UTF-16 with a byte-order mark, with LF or CRLF line ends.
#pragma once

#include <string>
#include <vector>

namespace gmg::text {

// One spoken word (or, in GENEA TSV, one "word" entry that may hold several words).
struct Word {
  double start = 0;  // seconds, finite, >= 0
  double end = 0;    // seconds, finite, >= start
  std::string text;  // as written in the file (UTF-8, trimmed); never empty, may be "#" (laughter)
};

enum class TranscriptFormat { Auto, Tsv, TextGrid, Json };

// "auto", "tsv", "textgrid", "json" (ASCII case-insensitive); gmg::Error listing the choices
// otherwise.
TranscriptFormat parse_transcript_format(const std::string& name);

// Reads a transcript. Auto picks the reader by extension (ASCII case-insensitive):
// .tsv/.txt -> TSV, .textgrid -> TextGrid, .json -> JSON (read_json_transcript: Whisper, WhisperX
// or Google); any other extension is a gmg::Error that suggests --transcript-format. `tier` names
// the TextGrid tier to read ("" = read_textgrid's default); given with another format it is an
// error, since it would silently mean nothing.
std::vector<Word> read_transcript(const std::string& path, TranscriptFormat format = TranscriptFormat::Auto,
                                  const std::string& tier = "");

// GENEA TSV: one word a line, `start<TAB>end<TAB>word`, no header. Everything after the second
// tab is the word (it may contain spaces and tabs; it is trimmed). A line without any tab is
// split on its first two runs of spaces instead. Blank lines are ignored; a line whose word is
// empty after trimming is silence and dropped. "#" (laughter) is kept as a word.
// Errors (with file and line): fewer than 3 fields, a non-numeric / NaN / infinite time, a
// negative time, end before start.
std::vector<Word> read_tsv(const std::string& path);

// Praat TextGrid, long or short text format (UTF-8 or UTF-16). Reads the IntervalTier named
// `tier` when given (exact name, else the one name equal ignoring ASCII case and surrounding
// spaces). Without one: the tier named "words" (ASCII case-insensitive); when there is none, the
// one tier whose name ends in "words" (e.g. MFA's "speaker - words"); else the only
// IntervalTier of the file. Intervals whose text is empty or only whitespace are silence and
// dropped; Praat's doubled quotes ("") inside a text become one quote.
// Errors (with file and line): not a text TextGrid (no `File type = "ooTextFile"` /
// `Object class = "TextGrid"`), no such tier or no tier to choose (the message lists the tiers
// found with their classes), a chosen tier that is not an IntervalTier, a malformed or truncated
// structure, a non-numeric / NaN time, an interval that ends before it starts.
std::vector<Word> read_textgrid(const std::string& path, const std::string& tier = "");

// Google speech-to-text JSON (GENEA 2020 / Trinity): a top-level array of results, or an object
// with a "results" array; each result's alternatives[0].words[] holds
// {"start_time": "1.500s", "end_time": "1.800s", "word": "hello"}. The camelCase keys
// "startTime"/"endTime" are accepted too. A time is a string of seconds with an optional "s"
// suffix, a number of seconds, or an object {"seconds": "1", "nanos": 500000000} (each member
// a string or number, a missing member is 0). A result without alternatives or without words
// contributes no words.
// Errors: invalid JSON, including a number beyond double range such as 1e309 ("file: byte N:
// invalid JSON (...)", engine/core/json.h), wrong structure or a missing field (the message gives
// the JSON location, e.g. "[2].alternatives[0].words[5]"), a bad time.
std::vector<Word> read_google_json(const std::string& path);

// Whisper JSON (openai-whisper run with word timestamps: segments[].words[] with "word",
// "start", "end") and WhisperX JSON (the same, and word_segments[]; segments[].words[] is read
// when present, else word_segments[]). Words are trimmed (Whisper starts them with a space);
// empty ones are dropped. WhisperX leaves out "start" and "end" for words its aligner cannot
// place (numbers written as digits): such a word takes the gap between its timed neighbours in
// its segment (start = the previous word's end or the segment's start, end = the next word's
// start or the segment's end), so the transcript keeps every word; a word with no time around it
// at all is dropped. A file with no segments is a silent clip (zero words).
// Errors (with the JSON location, e.g. "segments[3].words[2]"): invalid JSON, segments without
// any "words" (Whisper run without word timestamps: the message says how to get them), a word
// without "word", a time that is not a number, negative, or only one of start/end, end before
// start.
std::vector<Word> read_whisper_json(const std::string& path);

// A .json transcript of any kind: Whisper/WhisperX when the top level is an object with
// "segments" or "word_segments", else Google speech JSON.
std::vector<Word> read_json_transcript(const std::string& path);

// The readers for a file's bytes already in memory (what read_tsv, read_textgrid,
// read_google_json and read_json_transcript do after reading the file); `name` labels errors.
std::vector<Word> parse_tsv(const std::string& bytes, const std::string& name);
std::vector<Word> parse_textgrid(const std::string& bytes, const std::string& name, const std::string& tier = "");
std::vector<Word> parse_google_json(const std::string& bytes, const std::string& name);
std::vector<Word> parse_json_transcript(const std::string& bytes, const std::string& name);

// Throws gmg::Error naming `path` when some word ends after duration_s + tolerance_s, i.e. the
// transcript runs past the end of the audio (usually a transcript of another recording).
void check_transcript_fits(const std::vector<Word>& words, double duration_s, const std::string& path,
                           double tolerance_s = 0.05);

}  // namespace gmg::text
