// Whisper and WhisperX JSON transcripts: word timings from segments[].words[] or word_segments[],
// and the JSON front door that tells them from Google speech JSON.
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/json.h"
#include "engine/core/strings.h"
#include "text/json_words.h"
#include "text/text_file.h"
#include "text/transcript.h"
#include "text/transcript_util.h"

namespace gmg::text {

using detail::check_word_order;
using detail::format_seconds;
using detail::json_fail;
using detail::json_word_text;
using detail::sort_words;

namespace {

using nlohmann::json;

// A word as the file gives it: times may be missing (WhisperX leaves out the times of words its
// aligner has no characters for, such as numbers written as digits).
struct RawWord {
  std::optional<double> start, end;
  std::string text;
};

std::optional<double> optional_time(const json& w, const char* key, const std::string& path, const std::string& where) {
  const auto it = w.find(key);
  if (it == w.end() || it->is_null()) return std::nullopt;
  if (!it->is_number()) json_fail(path, where + "." + key, "expected a number of seconds, found " + it->dump());
  const double t = it->get<double>();
  if (!std::isfinite(t)) json_fail(path, where + "." + key, "time is not finite");
  if (t < 0) json_fail(path, where + "." + key, "negative time " + format_seconds(t));
  return t;
}

RawWord raw_word(const json& w, const std::string& path, const std::string& where) {
  std::string text = json_word_text(w, path, where);
  RawWord r{optional_time(w, "start", path, where), optional_time(w, "end", path, where), std::move(text)};
  if (r.start.has_value() != r.end.has_value())
    json_fail(
        path, where,
        std::string("has \"") + (r.start ? "start" : "end") + "\" but no \"" + (r.start ? "end" : "start") + "\"");
  if (r.start) check_word_order(r.text, *r.start, *r.end, path, where);
  return r;
}

// Appends the words of one sequence (a segment's words, or word_segments). An untimed word takes
// the gap between its timed neighbours in the sequence (or the segment's bounds, `lo`/`hi`): that
// is where it was spoken, so a keyword in it lands within the gap. A word with no bound at all is
// dropped.
void append_sequence(const std::vector<RawWord>& seq, std::optional<double> lo, std::optional<double> hi,
                     std::vector<Word>& out) {
  for (std::size_t i = 0; i < seq.size(); ++i) {
    const RawWord& w = seq[i];
    if (w.text.empty()) continue;
    if (w.start) {
      out.push_back(Word{*w.start, *w.end, w.text});
      continue;
    }
    std::optional<double> before = lo, after = hi;
    for (std::size_t k = i; k-- > 0;)
      if (seq[k].end) {
        before = seq[k].end;
        break;
      }
    for (std::size_t k = i + 1; k < seq.size(); ++k)
      if (seq[k].start) {
        after = seq[k].start;
        break;
      }
    if (!before && !after) continue;
    const double start = before ? *before : *after;
    out.push_back(Word{start, std::max(start, after ? *after : start), w.text});
  }
}

std::vector<RawWord> raw_words(const json& list, const std::string& path, const std::string& where) {
  if (!list.is_array()) json_fail(path, where, "expected an array of words");
  std::vector<RawWord> out;
  for (std::size_t k = 0; k < list.size(); ++k)
    out.push_back(raw_word(list[k], path, where + "[" + std::to_string(k) + "]"));
  return out;
}

// segments[].words[]; false when no segment has "words" (Whisper run without word timestamps).
bool segment_words(const json& segments, const std::string& path, std::vector<Word>& out) {
  if (!segments.is_array()) json_fail(path, "segments", "expected an array of segments");
  bool any = false;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const json& s = segments[i];
    const std::string where = "segments[" + std::to_string(i) + "]";
    if (!s.is_object()) json_fail(path, where, "expected a segment object");
    const auto words = s.find("words");
    if (words == s.end() || words->is_null()) continue;
    any = true;
    append_sequence(raw_words(*words, path, where + ".words"), optional_time(s, "start", path, where),
                    optional_time(s, "end", path, where), out);
  }
  return any;
}

bool is_whisper(const json& doc) {
  return doc.is_object() && (doc.contains("segments") || doc.contains("word_segments"));
}

std::vector<Word> whisper_words(const json& doc, const std::string& path) {
  std::vector<Word> words;
  const auto segments = doc.find("segments");
  const bool from_segments = segments != doc.end() && segment_words(*segments, path, words);
  if (!from_segments) {
    const auto ws = doc.find("word_segments");
    if (ws != doc.end()) {
      append_sequence(raw_words(*ws, path, "word_segments"), std::nullopt, std::nullopt, words);
    } else if (segments != doc.end() && !segments->empty()) {
      throw Error(path +
                  ": Whisper JSON without word timings (its segments have no \"words\"); the engine needs a time "
                  "for every word: transcribe with word timestamps (whisper --word_timestamps True) or align with "
                  "WhisperX");
    }
  }
  sort_words(words);
  return words;
}

}  // namespace

std::vector<Word> read_whisper_json(const std::string& path) {
  const json doc = parse_json_text(detail::read_text_file(path), path);
  if (!is_whisper(doc)) throw Error(path + ": not a Whisper JSON (no \"segments\" or \"word_segments\")");
  return whisper_words(doc, path);
}

std::vector<Word> read_json_transcript(const std::string& path) {
  return parse_json_transcript(read_file_bytes(path), path);
}

std::vector<Word> parse_json_transcript(const std::string& bytes, const std::string& name) {
  const json doc = parse_json_text(detail::decode_to_utf8(bytes, name), name);
  if (is_whisper(doc)) return whisper_words(doc, name);
  return parse_google_json(bytes, name);  // parses again: transcripts are small
}

}  // namespace gmg::text
