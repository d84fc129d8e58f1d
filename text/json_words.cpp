#include "text/json_words.h"

#include "engine/core/strings.h"
#include "text/transcript_util.h"

namespace gmg::text::detail {

std::string json_word_text(const nlohmann::json& w, const std::string& path, const std::string& where) {
  if (!w.is_object()) json_fail(path, where, "expected a word object");
  const auto text = w.find("word");
  if (text == w.end()) json_fail(path, where, "missing \"word\"");
  if (!text->is_string()) json_fail(path, where + ".word", "expected a string");
  return std::string(trim(text->get_ref<const std::string&>()));
}

void check_word_order(const std::string& text, double start, double end, const std::string& path,
                      const std::string& where) {
  if (end < start)
    json_fail(path, where,
              "word " + quote_field(text) + " ends (" + format_seconds(end) + " s) before it starts (" +
                  format_seconds(start) + " s)");
}

}  // namespace gmg::text::detail
