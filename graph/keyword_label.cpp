#include "graph/keyword_label.h"

#include <deque>
#include <limits>
#include <mutex>
#include <unordered_map>

#include "engine/core/error.h"

namespace gmg {
namespace {

// Texts by id (id 0 is the empty text; a deque keeps references to its elements valid as it
// grows) and ids by text (keys view the deque's strings).
struct Labels {
  std::mutex mutex;
  std::deque<std::string> texts{std::string()};
  std::unordered_map<std::string_view, std::uint32_t> ids;
};

Labels& labels() {
  static Labels* table = new Labels();  // never destroyed: labels may be read during exit
  return *table;
}

}  // namespace

KeywordLabel::KeywordLabel(std::string_view text) {
  if (text.empty()) return;
  Labels& t = labels();
  const std::lock_guard<std::mutex> lock(t.mutex);
  const auto hit = t.ids.find(text);
  if (hit != t.ids.end()) {
    id_ = hit->second;
    return;
  }
  if (t.texts.size() >= std::numeric_limits<std::uint32_t>::max()) throw Error("too many distinct keyword labels");
  id_ = static_cast<std::uint32_t>(t.texts.size());
  t.texts.emplace_back(text);
  t.ids.emplace(t.texts.back(), id_);
}

const std::string& KeywordLabel::str() const {
  Labels& t = labels();
  const std::lock_guard<std::mutex> lock(t.mutex);
  return t.texts[id_];
}

}  // namespace gmg
