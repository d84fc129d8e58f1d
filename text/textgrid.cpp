// Praat TextGrid transcripts (long and short text formats): the words tier, or the tier asked for;
// and the phones tier when there is one (text/phones.h).
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "text/phones.h"
#include "text/text_file.h"
#include "text/transcript.h"
#include "text/transcript_util.h"

namespace gmg::text {

using detail::format_seconds;
using detail::quote_field;
using detail::sort_words;

namespace {

// TextGrid: a token stream of the values in the file (numbers, "strings", <flags>), the way Praat
// reads its text formats. In the long format, labels such as `xmin =`, `intervals [3]:` and
// `item []:` are skipped; a bare word right after `=` is a bad value.

struct Token {
  enum Kind { Number, String, Flag, Label, Bad, End } kind = End;
  std::string text;  // the string's content (unescaped), the flag's name, or the raw word
  double value = 0;  // for Number
  long line = 0;     // 1-based line where the token starts
};

class TextGridLexer {
 public:
  TextGridLexer(const std::string& text, const std::string& path) : s_(text), path_(path) {}

  Token next() {
    skip_blanks();
    Token t;
    t.line = line_;
    if (pos_ >= s_.size()) {
      t.kind = Token::End;
      return t;
    }
    char c = s_[pos_];
    if (c == '"') {
      t.kind = Token::String;
      ++pos_;
      for (;;) {
        if (pos_ >= s_.size()) throw Error(error_at_line(path_, t.line, "unterminated text (missing closing quote)"));
        char d = s_[pos_++];
        if (d == '"') {
          if (pos_ < s_.size() && s_[pos_] == '"') {  // "" is a literal quote
            t.text += '"';
            ++pos_;
            continue;
          }
          break;
        }
        if (d == '\n') ++line_;
        t.text += d;
      }
      prev_was_equals_ = false;
      return t;
    }
    if (c == '<') {
      std::size_t close = s_.find('>', pos_);
      std::size_t eol = s_.find('\n', pos_);
      if (close != std::string::npos && (eol == std::string::npos || close < eol)) {
        t.kind = Token::Flag;
        t.text = s_.substr(pos_ + 1, close - pos_ - 1);
        pos_ = close + 1;
        prev_was_equals_ = false;
        return t;
      }
    }
    if (c == '[') {  // `[3]`, `[]`: an index label
      std::size_t close = s_.find(']', pos_);
      std::size_t eol = s_.find('\n', pos_);
      if (close != std::string::npos && (eol == std::string::npos || close < eol)) {
        t.kind = Token::Label;
        t.text = s_.substr(pos_, close + 1 - pos_);
        pos_ = close + 1;
        prev_was_equals_ = false;
        return t;
      }
    }
    std::size_t start = pos_;
    while (pos_ < s_.size() && !is_ascii_space(s_[pos_]) && s_[pos_] != '"' && !(pos_ > start && s_[pos_] == '[')) {
      ++pos_;
    }
    t.text = s_.substr(start, pos_ - start);
    bool numeric_looking = c == '+' || c == '-' || c == '.' || (c >= '0' && c <= '9');
    if (auto v = numeric_looking ? parse_number(t.text) : std::nullopt) {
      t.kind = Token::Number;
      t.value = *v;
    } else if (numeric_looking || prev_was_equals_) {
      t.kind = Token::Bad;
    } else {
      t.kind = Token::Label;
    }
    prev_was_equals_ = t.text == "=";
    return t;
  }

 private:
  void skip_blanks() {
    while (pos_ < s_.size() && is_ascii_space(s_[pos_])) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  const std::string& s_;
  const std::string& path_;
  std::size_t pos_ = 0;
  long line_ = 1;
  bool prev_was_equals_ = false;
};

struct Interval {
  double xmin = 0, xmax = 0;
  std::string text;
  long line = 0;  // line of the interval's xmin
};

struct Tier {
  std::string cls, name;
  long line = 0;  // line of the tier's class
  std::vector<Interval> intervals;
};

class TextGridParser {
 public:
  TextGridParser(const std::string& text, const std::string& path) : lex_(text, path), path_(path) {}

  std::vector<Tier> parse() {
    // Header: File type = "ooTextFile", Object class = "TextGrid".
    Token t = raw();
    while (t.kind == Token::Label) t = raw();
    if (t.kind != Token::String || t.text != "ooTextFile")
      throw Error(error_at_line(path_, t.kind == Token::End ? 1 : t.line,
                                "not a Praat text TextGrid (File type = \"ooTextFile\" missing)"));
    t = raw();
    while (t.kind == Token::Label) t = raw();
    if (t.kind != Token::String) throw Error(error_at_line(path_, last_line(t), "Object class = \"TextGrid\" missing"));
    if (t.text.rfind("TextGrid", 0) != 0)
      throw Error(error_at_line(path_, t.line, "object class is " + quote_field(t.text) + ", not a TextGrid"));
    // Long format: labels (`xmin = 0`) from here on; short format: bare values.
    Token after = raw();
    long_format_ = after.kind == Token::Label;
    pending_ = after;
    has_pending_ = true;

    number("the TextGrid's xmin");
    number("the TextGrid's xmax");
    Token flag = value("the tiers flag <exists>");
    if (flag.kind != Token::Flag || (flag.text != "exists" && flag.text != "absent"))
      throw unexpected(flag, "the tiers flag <exists> or <absent>");
    std::vector<Tier> tiers;
    if (flag.text == "absent") return tiers;
    long n_tiers = count("the number of tiers");
    for (long i = 1; i <= n_tiers; ++i) {
      Tier tier;
      Token cls = value("the class of tier " + std::to_string(i));
      if (cls.kind != Token::String) throw unexpected(cls, "the class of tier " + std::to_string(i));
      tier.cls = cls.text;
      tier.line = cls.line;
      Token name = value("the name of tier " + std::to_string(i));
      if (name.kind != Token::String) throw unexpected(name, "the name of tier " + std::to_string(i));
      tier.name = name.text;
      std::string what = "tier " + quote_field(tier.name);
      number("the xmin of " + what);
      number("the xmax of " + what);
      if (tier.cls == "IntervalTier") {
        long n = count("the number of intervals of " + what);
        // No reserve from the count: intervals are stored as they are read, so a file claiming
        // 10^8 of them costs only what it holds.
        for (long k = 1; k <= n; ++k) {
          std::string where = "interval " + std::to_string(k) + " of " + what;
          Interval iv;
          iv.xmin = number("the xmin of " + where, &iv.line);
          iv.xmax = number("the xmax of " + where);
          Token txt = value("the text of " + where);
          if (txt.kind != Token::String) throw unexpected(txt, "the text of " + where + " (\"...\")");
          iv.text = txt.text;
          tier.intervals.push_back(std::move(iv));
        }
      } else if (tier.cls == "TextTier") {
        long n = count("the number of points of " + what);
        for (long k = 1; k <= n; ++k) {
          std::string where = "point " + std::to_string(k) + " of " + what;
          number("the time of " + where);
          Token mark = value("the mark of " + where);
          if (mark.kind != Token::String) throw unexpected(mark, "the mark of " + where);
        }
      } else {
        throw Error(error_at_line(
            path_, cls.line, "unknown tier class " + quote_field(tier.cls) + " (expected IntervalTier or TextTier)"));
      }
      tiers.push_back(std::move(tier));
    }
    return tiers;
  }

 private:
  Token raw() {
    if (has_pending_) {
      has_pending_ = false;
      return pending_;
    }
    Token t = lex_.next();
    if (t.kind != Token::End) last_line_ = t.line;
    return t;
  }

  long last_line(const Token& t) const { return t.kind == Token::End ? last_line_ : t.line; }

  // The next value token (labels skipped in the long format; an error in the short one).
  Token value(const std::string& what) {
    Token t = raw();
    while (t.kind == Token::Label && long_format_) t = raw();
    if (t.kind == Token::End)
      throw Error(
          error_at_line(path_, last_line_, "unexpected end of file (truncated TextGrid?) while reading " + what));
    if (t.kind == Token::Bad || t.kind == Token::Label) {
      const bool nonfinite = detail::names_non_finite(t.text);
      throw Error(error_at_line(path_, t.line,
                                "malformed value " + quote_field(t.text) + " for " + what +
                                    (nonfinite ? " (not a finite number)" : " (not a number)")));
    }
    return t;
  }

  Error unexpected(const Token& t, const std::string& what) const {
    std::string found = t.kind == Token::Number   ? "the number " + t.text
                        : t.kind == Token::String ? "the text " + quote_field(t.text)
                        : t.kind == Token::Flag   ? "<" + t.text + ">"
                                                  : quote_field(t.text);
    return Error(error_at_line(path_, t.line, "malformed TextGrid: expected " + what + ", found " + found));
  }

  double number(const std::string& what, long* line = nullptr) {
    Token t = value(what);
    if (t.kind != Token::Number) throw unexpected(t, what + " (a number)");
    if (line) *line = t.line;
    return t.value;
  }

  long count(const std::string& what) {
    Token t = value(what);
    if (t.kind != Token::Number || t.value < 0 || t.value != std::floor(t.value) || t.value > 1e8)
      throw unexpected(t, what + " (a count)");
    return static_cast<long>(t.value);
  }

  TextGridLexer lex_;
  const std::string& path_;
  bool long_format_ = true;
  Token pending_;
  bool has_pending_ = false;
  long last_line_ = 1;
};

// "phones" (IntervalTier), "notes" (TextTier): for the message when no tier can be chosen.
std::string tier_list(const std::vector<Tier>& tiers) {
  std::string list;
  for (const Tier& t : tiers) list += (list.empty() ? "" : ", ") + quote_field(t.name) + " (" + t.cls + ")";
  return list.empty() ? std::string("none") : list;
}

// The tier named `wanted`: the exact name, else the one name equal to it ignoring ASCII case and
// surrounding spaces.
const Tier* named_tier(const std::vector<Tier>& tiers, const std::string& wanted, const std::string& path) {
  for (const Tier& t : tiers)
    if (t.name == wanted) return &t;
  const Tier* found = nullptr;
  int n = 0;
  for (const Tier& t : tiers)
    if (ascii_lower(trim(t.name)) == ascii_lower(trim(wanted))) {
      found = &t;
      ++n;
    }
  if (n != 1) throw Error(path + ": no tier named " + quote_field(wanted) + " (tiers found: " + tier_list(tiers) + ")");
  return found;
}

// Without --tier: "words", else the one tier ending in "words", else the only interval tier.
const Tier* default_tier(const std::vector<Tier>& tiers, const std::string& path) {
  for (const Tier& t : tiers)
    if (ascii_lower(trim(t.name)) == "words") return &t;
  const Tier* candidate = nullptr;
  int n = 0;
  for (const Tier& t : tiers) {  // e.g. Montreal Forced Aligner's "speaker - words"
    std::string name = ascii_lower(trim(t.name));
    if (name.size() > 5 && name.compare(name.size() - 5, 5, "words") == 0) {
      candidate = &t;
      ++n;
    }
  }
  if (n == 1) return candidate;
  const Tier* only = nullptr;
  int intervals = 0;
  for (const Tier& t : tiers)
    if (t.cls == "IntervalTier") {
      only = &t;
      ++intervals;
    }
  if (intervals == 1) return only;
  throw Error(path + ": no tier named \"words\" and " + (intervals ? "more than one" : "no") +
              " interval tier to read instead (tiers found: " + tier_list(tiers) + "); choose one with --tier NAME");
}

// The words of an interval tier: its intervals with text, checked (an end before its start, a
// negative start), sorted by start.
std::vector<Word> tier_words(const Tier& chosen, const std::string& path) {
  std::vector<Word> words;
  for (const Interval& iv : chosen.intervals) {
    if (iv.xmax < iv.xmin)
      throw Error(error_at_line(path, iv.line,
                                "interval " + quote_field(iv.text) + " ends (" + format_seconds(iv.xmax) +
                                    " s) before it starts (" + format_seconds(iv.xmin) + " s)"));
    if (iv.xmin < 0)
      throw Error(error_at_line(
          path, iv.line, "interval " + quote_field(iv.text) + " starts at a negative time " + format_seconds(iv.xmin)));
    std::string_view t = trim(iv.text);
    if (t.empty()) continue;  // silence
    words.push_back(Word{iv.xmin, iv.xmax, std::string(t)});
  }
  sort_words(words);
  return words;
}

// The phones tier: named "phones", else the one interval tier whose name ends in "phones"; null
// when there is none.
const Tier* phones_tier(const std::vector<Tier>& tiers) {
  for (const Tier& t : tiers)
    if (t.cls == "IntervalTier" && ascii_lower(trim(t.name)) == "phones") return &t;
  const Tier* found = nullptr;
  int n = 0;
  for (const Tier& t : tiers) {
    const std::string name = ascii_lower(trim(t.name));
    if (t.cls == "IntervalTier" && name.size() > 6 && name.compare(name.size() - 6, 6, "phones") == 0) {
      found = &t;
      ++n;
    }
  }
  return n == 1 ? found : nullptr;
}

}  // namespace

std::vector<Phone> parse_textgrid_phones(const std::string& bytes, const std::string& path) {
  const std::string text = detail::decode_to_utf8(bytes, path);
  const std::vector<Tier> tiers = TextGridParser(text, path).parse();
  std::vector<Phone> phones;
  const Tier* tier = phones_tier(tiers);
  if (!tier) return phones;
  for (Word& w : tier_words(*tier, path)) {
    std::string symbol = phone_symbol(w.text);
    if (!symbol.empty()) phones.push_back({w.start, w.end, std::move(symbol)});
  }
  return phones;
}

std::vector<Word> read_textgrid(const std::string& path, const std::string& tier) {
  return parse_textgrid(read_file_bytes(path), path, tier);
}

std::vector<Word> parse_textgrid(const std::string& bytes, const std::string& path, const std::string& tier) {
  const std::string text = detail::decode_to_utf8(bytes, path);
  std::vector<Tier> tiers = TextGridParser(text, path).parse();
  const Tier* chosen = tier.empty() ? default_tier(tiers, path) : named_tier(tiers, tier, path);
  if (chosen->cls != "IntervalTier")
    throw Error(
        error_at_line(path, chosen->line,
                      "the tier " + quote_field(chosen->name) + " is a " + chosen->cls + ", not an IntervalTier"));
  return tier_words(*chosen, path);
}

}  // namespace gmg::text
