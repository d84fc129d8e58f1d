// The transcript front door: format names, dispatch by extension, the fit to the audio, and the
// helpers the readers share. The readers: tsv.cpp, textgrid.cpp, google_json.cpp, whisper_json.cpp.
#include "text/transcript.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "text/transcript_util.h"

namespace gmg::text {

namespace detail {

std::string format_seconds(double t) {
  std::ostringstream os;
  os.precision(10);
  os << t;
  return os.str();
}

void sort_words(std::vector<Word>& words) {
  std::stable_sort(words.begin(), words.end(), [](const Word& a, const Word& b) { return a.start < b.start; });
}

void json_fail(const std::string& path, const std::string& where, const std::string& what) {
  throw Error(path + ": " + (where.empty() ? "" : where + ": ") + what);
}

std::string quote_field(std::string_view s) {
  // Escaped: the field of a binary file given as a transcript must not reach the terminal raw.
  std::string out = escape_nonprintable(s.substr(0, 60));
  if (s.size() > 60) out += "...";
  return "\"" + out + "\"";
}

bool names_non_finite(std::string_view field) {
  std::string lower = ascii_lower(trim(field));
  if (!lower.empty() && (lower.front() == '+' || lower.front() == '-')) lower.erase(0, 1);
  return lower == "nan" || lower == "inf" || lower == "infinity";
}

}  // namespace detail

using detail::format_seconds;
using detail::quote_field;

TranscriptFormat parse_transcript_format(const std::string& name) {
  std::string n = ascii_lower(trim(name));
  if (n == "auto") return TranscriptFormat::Auto;
  if (n == "tsv") return TranscriptFormat::Tsv;
  if (n == "textgrid") return TranscriptFormat::TextGrid;
  if (n == "json") return TranscriptFormat::Json;
  throw Error("unknown transcript format " + quote_field(name) + " (expected one of: auto, tsv, textgrid, json)");
}

std::vector<Word> read_transcript(const std::string& path, TranscriptFormat format, const std::string& tier) {
  if (format == TranscriptFormat::Auto) {
    std::string ext = ascii_lower(std::filesystem::path(path).extension().string());
    if (ext == ".tsv" || ext == ".txt") {
      format = TranscriptFormat::Tsv;
    } else if (ext == ".textgrid") {
      format = TranscriptFormat::TextGrid;
    } else if (ext == ".json") {
      format = TranscriptFormat::Json;
    } else {
      throw Error(path + ": cannot tell the transcript format from the extension " +
                  (ext.empty() ? std::string("(none)") : quote_field(ext)) +
                  " (known: .tsv, .txt, .TextGrid, .json); use --transcript-format tsv|textgrid|json");
    }
  }
  if (!tier.empty() && format != TranscriptFormat::TextGrid)
    throw Error(path + ": a tier (" + quote_field(tier) + ") was given, but only a TextGrid transcript has tiers");
  switch (format) {
    case TranscriptFormat::Tsv:
      return read_tsv(path);
    case TranscriptFormat::TextGrid:
      return read_textgrid(path, tier);
    case TranscriptFormat::Json:
      return read_json_transcript(path);
    case TranscriptFormat::Auto:
      break;
  }
  throw Error(path + ": unknown transcript format");
}

void check_transcript_fits(const std::vector<Word>& words, double duration_s, const std::string& path,
                           double tolerance_s) {
  for (const Word& w : words) {
    if (w.end > duration_s + tolerance_s)
      throw Error(path + ": the transcript runs past the end of the audio: word " + quote_field(w.text) + " ends at " +
                  format_seconds(w.end) + " s but the audio lasts " + format_seconds(duration_s) +
                  " s (a transcript of another recording?)");
  }
}

}  // namespace gmg::text
