#include "text/keywords.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <unordered_map>

#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "text/default_lexicon.h"
#include "text/text_file.h"

namespace gmg::text {

namespace {

enum class Kind { WordChar, Joiner, Space, Punct };

struct Unit {
  Kind kind;
  std::string bytes;  // what to output for WordChar / Joiner
};

// Splits UTF-8 text into classified characters.
std::vector<Unit> classify(const std::string& w) {
  std::vector<Unit> units;
  std::size_t i = 0;
  while (i < w.size()) {
    auto c = static_cast<unsigned char>(w[i]);
    if (c < 0x80) {
      if ((c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z')) {
        char lower = (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : static_cast<char>(c);
        units.push_back({Kind::WordChar, std::string(1, lower)});
      } else if (c == '\'' || c == '-') {
        units.push_back({Kind::Joiner, std::string(1, static_cast<char>(c))});
      } else if (is_ascii_space(static_cast<char>(c))) {
        units.push_back({Kind::Space, ""});
      } else {
        units.push_back({Kind::Punct, ""});
      }
      ++i;
      continue;
    }
    // A multi-byte UTF-8 character; bytes that do not form one (decode_utf8: also overlong forms
    // and surrogates) are taken one by one, as word characters.
    const std::optional<Utf8Char> ch = decode_utf8(w, i);
    if (!ch) {
      units.push_back({Kind::WordChar, std::string(1, static_cast<char>(c))});
      ++i;
      continue;
    }
    const char32_t cp = ch->code_point;
    std::string seq = w.substr(i, ch->length);
    i += ch->length;
    switch (cp) {
      case 0x2018:
      case 0x2019:
      case 0x02BC:  // typographic apostrophes
        units.push_back({Kind::Joiner, "'"});
        break;
      case 0x2010:
      case 0x2011:  // Unicode hyphens
        units.push_back({Kind::Joiner, "-"});
        break;
      case 0x00A0:
      case 0x2002:
      case 0x2003:
      case 0x2009:
      case 0x200A:
      case 0x202F:
      case 0x3000:  // spaces
        units.push_back({Kind::Space, ""});
        break;
      case 0x00AB:
      case 0x00BB:
      case 0x201A:
      case 0x201C:
      case 0x201D:
      case 0x201E:
      case 0x2012:
      case 0x2013:
      case 0x2014:
      case 0x2015:
      case 0x2026:
      case 0x00BF:
      case 0x00A1:
      case 0x200B:
      case 0xFEFF:  // quotes, dashes, ellipsis, inverted marks, ZW
        units.push_back({Kind::Punct, ""});
        break;
      default:
        units.push_back({Kind::WordChar, std::move(seq)});
    }
  }
  return units;
}

std::string join(const std::vector<std::string>& tokens) {
  std::string out;
  for (const std::string& t : tokens) {
    if (!out.empty()) out += ' ';
    out += t;
  }
  return out;
}

}  // namespace

std::string normalize_word(const std::string& w) {
  const std::vector<Unit> units = classify(w);
  std::string out;
  bool pending_space = false;
  for (std::size_t i = 0; i < units.size(); ++i) {
    const Unit& u = units[i];
    switch (u.kind) {
      case Kind::WordChar:
        if (pending_space && !out.empty()) out += ' ';
        pending_space = false;
        out += u.bytes;
        break;
      case Kind::Space:
        pending_space = true;
        break;
      case Kind::Punct:
        break;
      case Kind::Joiner: {
        // Kept when it directly follows a word character and the run of joiners it starts is
        // directly followed by a word character.
        if (i == 0 || units[i - 1].kind != Kind::WordChar) break;
        std::size_t j = i;
        while (j < units.size() && units[j].kind == Kind::Joiner) ++j;
        if (j < units.size() && units[j].kind == Kind::WordChar) out += u.bytes;
        i = j - 1;
        break;
      }
    }
  }
  return out;
}

std::vector<std::string> normalize_tokens(const std::string& text) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && is_ascii_space(text[i])) ++i;
    std::size_t start = i;
    while (i < text.size() && !is_ascii_space(text[i])) ++i;
    if (i == start) break;
    // normalize_word may still split on non-ASCII spaces: keep each piece.
    std::string n = normalize_word(text.substr(start, i - start));
    std::size_t p = 0;
    while (p < n.size()) {
      std::size_t sp = n.find(' ', p);
      if (sp == std::string::npos) sp = n.size();
      if (sp > p) tokens.push_back(n.substr(p, sp - p));
      p = sp + 1;
    }
  }
  return tokens;
}

bool Lexicon::add(const std::string& phrase) {
  std::vector<std::string> tokens = normalize_tokens(phrase);
  if (tokens.empty()) return false;
  if (std::find(phrases.begin(), phrases.end(), tokens) != phrases.end()) return false;
  phrases.push_back(std::move(tokens));
  return true;
}

bool Lexicon::contains(const std::string& phrase) const {
  std::vector<std::string> tokens = normalize_tokens(phrase);
  if (tokens.empty()) return false;
  return std::find(phrases.begin(), phrases.end(), tokens) != phrases.end();
}

Lexicon load_lexicon(const std::string& path) { return parse_lexicon(detail::read_text_file(path), path); }

Lexicon parse_lexicon(const std::string& text, const std::string& path) {
  const std::vector<std::string> lines = split_lines(text);
  Lexicon lex;
  std::set<std::vector<std::string>> seen;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string line = lines[i];
    if (std::size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    if (trim(line).empty()) continue;
    std::vector<std::string> tokens = normalize_tokens(line);
    if (tokens.empty())
      throw Error(error_at_line(path, static_cast<long>(i + 1),
                                "keyword \"" + std::string(trim(line)) + "\" has no letters or digits"));
    if (seen.insert(tokens).second) lex.phrases.push_back(std::move(tokens));
  }
  if (lex.empty()) throw Error(path + ": the keyword lexicon holds no keywords");
  return lex;
}

Lexicon default_lexicon() {
  static const Lexicon lexicon = parse_lexicon(kDefaultLexiconText, kDefaultLexiconName);
  return lexicon;
}

std::vector<KeywordEvent> detect_keywords(const std::vector<Word>& words, const Lexicon& lexicon) {
  struct Token {
    std::string text;
    std::size_t word;  // index into words
  };
  std::vector<Token> tokens;
  for (std::size_t k = 0; k < words.size(); ++k)
    for (std::string& t : normalize_tokens(words[k].text)) tokens.push_back({std::move(t), k});

  // Phrases by first token, longest first (ties: lexicon order).
  std::unordered_map<std::string, std::vector<const std::vector<std::string>*>> by_first;
  for (const auto& p : lexicon.phrases)
    if (!p.empty()) by_first[p.front()].push_back(&p);
  for (auto& [first, list] : by_first)
    std::stable_sort(list.begin(), list.end(), [](const auto* a, const auto* b) { return a->size() > b->size(); });

  std::vector<KeywordEvent> events;
  std::size_t prev_end = static_cast<std::size_t>(-1);  // token index right after the last match
  std::string prev_keyword;
  std::size_t i = 0;
  while (i < tokens.size()) {
    const std::vector<std::string>* match = nullptr;
    if (auto it = by_first.find(tokens[i].text); it != by_first.end()) {
      for (const auto* p : it->second) {
        if (i + p->size() > tokens.size()) continue;
        bool ok = true;
        for (std::size_t k = 1; k < p->size() && ok; ++k) ok = tokens[i + k].text == (*p)[k];
        if (ok) {
          match = p;
          break;
        }
      }
    }
    if (!match) {
      ++i;
      continue;
    }
    std::string keyword = join(*match);
    if (!(prev_end == i && prev_keyword == keyword)) events.push_back({words[tokens[i].word].start, keyword});
    i += match->size();
    prev_end = i;
    prev_keyword = std::move(keyword);
  }
  return events;
}

std::vector<KeywordFrame> keyword_frames(const std::vector<KeywordEvent>& ev, double fps, int num_frames) {
  if (!(fps > 0) || !std::isfinite(fps))
    throw Error("keyword_frames: the frame rate must be positive, got " + std::to_string(fps));
  std::vector<KeywordFrame> frames;
  if (num_frames <= 0) return frames;
  std::set<int> used;
  for (const KeywordEvent& e : ev) {
    double f = std::floor(e.time * fps + 0.5);
    if (!(f >= 0.0 && f < num_frames)) continue;  // also drops NaN
    const int frame = static_cast<int>(f);
    if (used.insert(frame).second) frames.push_back({frame, e.keyword});
  }
  std::stable_sort(frames.begin(), frames.end(),
                   [](const KeywordFrame& a, const KeywordFrame& b) { return a.frame < b.frame; });
  return frames;
}

}  // namespace gmg::text
