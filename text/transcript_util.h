// Internal helpers shared by the transcript readers (tsv, textgrid, google_json, whisper_json).
// Not part of the public API (namespace gmg::text::detail).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "text/transcript.h"

namespace gmg::text::detail {

// Seconds for a message, up to 10 significant digits ("1.5", "62.40000001").
std::string format_seconds(double t);

// Sorts by start time, stably: the readers' common contract (words with equal starts keep file
// order).
void sort_words(std::vector<Word>& words);

// Quotes a field for an error message, shortened to 60 bytes and "..." when long, its
// non-printable bytes escaped (escape_nonprintable).
std::string quote_field(std::string_view s);

// True when a field that failed to parse as a number names a non-finite one ("nan", "-inf",
// "+Infinity", ASCII case-insensitive), so the message can say "not a finite number".
bool names_non_finite(std::string_view field);

// Throws gmg::Error "path: where: what" for a JSON transcript ("path: what" when where is
// empty); `where` is the JSON location, e.g. "segments[3].words[2]".
[[noreturn]] void json_fail(const std::string& path, const std::string& where, const std::string& what);

}  // namespace gmg::text::detail
