// What the JSON transcript readers (google_json, whisper_json) check alike in a word object: its
// text, and that it does not end before it starts. Not part of the public API (gmg::text::detail).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace gmg::text::detail {

// The "word" of the word object `w` at JSON location `where`, trimmed. json_fail (transcript_util.h)
// when `w` is not an object ("expected a word object"), has no "word" or its "word" is not a string.
std::string json_word_text(const nlohmann::json& w, const std::string& path, const std::string& where);

// json_fail "word 'x' ends (1.2 s) before it starts (1.5 s)" when end < start.
void check_word_order(const std::string& text, double start, double end, const std::string& path,
                      const std::string& where);

}  // namespace gmg::text::detail
