// Google speech-to-text JSON transcripts (GENEA 2020 / Trinity): alternatives[0].words[].
#include <cmath>
#include <string>
#include <string_view>
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
using detail::quote_field;
using detail::sort_words;

namespace {

using nlohmann::json;

double json_time(const json& v, const std::string& path, const std::string& where) {
  auto number_of = [&](const json& x, const std::string& w, bool allow_suffix) -> double {
    if (x.is_number()) {
      double d = x.get<double>();
      if (!std::isfinite(d)) json_fail(path, w, "time is not finite");
      return d;
    }
    if (x.is_string()) {
      std::string_view s = trim(x.get_ref<const std::string&>());
      if (allow_suffix && !s.empty() && (s.back() == 's' || s.back() == 'S')) s.remove_suffix(1);
      if (auto d = parse_number(s)) return *d;
      json_fail(path, w,
                "bad time " + quote_field(x.get_ref<const std::string&>()) + " (expected seconds such as \"1.500s\")");
    }
    json_fail(path, w, "bad time " + x.dump() + " (expected a string, number or {seconds, nanos})");
  };
  if (v.is_object()) {
    double t = 0;
    if (auto it = v.find("seconds"); it != v.end()) t += number_of(*it, where + ".seconds", false);
    if (auto it = v.find("nanos"); it != v.end()) t += 1e-9 * number_of(*it, where + ".nanos", false);
    return t;
  }
  return number_of(v, where, true);
}

const json* find_either(const json& obj, const char* a, const char* b) {
  if (auto it = obj.find(a); it != obj.end()) return &*it;
  if (auto it = obj.find(b); it != obj.end()) return &*it;
  return nullptr;
}

}  // namespace

std::vector<Word> read_google_json(const std::string& path) { return parse_google_json(read_file_bytes(path), path); }

std::vector<Word> parse_google_json(const std::string& bytes, const std::string& path) {
  // Decoded first (a UTF-16 export is still JSON), then parsed with the engine's JSON errors.
  const json doc = parse_json_text(detail::decode_to_utf8(bytes, path), path);

  const json* results = nullptr;
  std::string base;
  if (doc.is_array()) {
    results = &doc;
  } else if (doc.is_object() && doc.contains("results")) {
    results = &doc["results"];
    base = "results";
  } else if (doc.is_object() && doc.contains("response") && doc["response"].is_object() &&
             doc["response"].contains("results")) {
    results = &doc["response"]["results"];
    base = "response.results";
  } else {
    json_fail(path, "",
              "expected a Google speech JSON: an array of results or an object with "
              "\"results\"");
  }
  if (!results->is_array()) json_fail(path, base, "expected an array of results");

  std::vector<Word> words;
  for (std::size_t r = 0; r < results->size(); ++r) {
    const json& result = (*results)[r];
    std::string where = base + "[" + std::to_string(r) + "]";
    if (!result.is_object()) json_fail(path, where, "expected a result object");
    auto alts = result.find("alternatives");
    if (alts == result.end() || alts->is_null()) continue;
    if (!alts->is_array()) json_fail(path, where + ".alternatives", "expected an array");
    if (alts->empty()) continue;
    const json& alt = (*alts)[0];
    where += ".alternatives[0]";
    if (!alt.is_object()) json_fail(path, where, "expected an object");
    auto ws = alt.find("words");
    if (ws == alt.end() || ws->is_null()) continue;
    if (!ws->is_array()) json_fail(path, where + ".words", "expected an array");
    for (std::size_t k = 0; k < ws->size(); ++k) {
      const json& w = (*ws)[k];
      std::string wh = where + ".words[" + std::to_string(k) + "]";
      if (!w.is_object()) json_fail(path, wh, "expected a word object");
      const json* st = find_either(w, "start_time", "startTime");
      const json* en = find_either(w, "end_time", "endTime");
      if (!st) json_fail(path, wh, "missing \"start_time\"");
      if (!en) json_fail(path, wh, "missing \"end_time\"");
      Word out;
      out.text = json_word_text(w, path, wh);
      out.start = json_time(*st, path, wh + ".start_time");
      out.end = json_time(*en, path, wh + ".end_time");
      if (out.start < 0) json_fail(path, wh, "negative start time " + format_seconds(out.start));
      check_word_order(out.text, out.start, out.end, path, wh);
      if (out.text.empty()) continue;
      words.push_back(std::move(out));
    }
  }
  sort_words(words);
  return words;
}

}  // namespace gmg::text
