// Internal helpers shared by the transcript readers (tsv.cpp, textgrid.cpp, google_json.cpp).
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

// Quotes a field for an error message, shortened to 60 bytes and "..." when long.
std::string quote_field(std::string_view s);

// True when a field that failed to parse as a number names a non-finite one ("nan", "-inf",
// "+Infinity", ASCII case-insensitive), so the message can say "not a finite number".
bool names_non_finite(std::string_view field);

}  // namespace gmg::text::detail
