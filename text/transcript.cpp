#include "text/transcript.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "text/text_file.h"

namespace gmg::text {

using detail::ascii_lower;
using detail::parse_number;
using detail::trim;

namespace {

std::string format_seconds(double t) {
  std::ostringstream os;
  os.precision(10);
  os << t;
  return os.str();
}

void sort_words(std::vector<Word>& words) {
  std::stable_sort(words.begin(), words.end(),
                   [](const Word& a, const Word& b) { return a.start < b.start; });
}

// Quotes a field for an error message, shortened when long.
std::string quote_field(std::string_view s) {
  std::string out(s.substr(0, 60));
  if (s.size() > 60) out += "...";
  return "\"" + out + "\"";
}

// ---------------------------------------------------------------------------------------------
// TSV

double tsv_time(std::string_view field, const char* which, const std::string& path, long line) {
  std::string_view f = trim(field);
  if (auto v = parse_number(f)) {
    if (*v < 0)
      throw Error(error_at_line(path, line, std::string("negative ") + which + " time " +
                                                std::string(f)));
    return *v;
  }
  std::string lower = ascii_lower(f);
  if (!lower.empty() && (lower.front() == '+' || lower.front() == '-')) lower.erase(0, 1);
  if (lower == "nan" || lower == "inf" || lower == "infinity")
    throw Error(error_at_line(path, line, std::string(which) + " time " + quote_field(f) +
                                              " is not a finite number"));
  throw Error(error_at_line(path, line, std::string(which) + " time " + quote_field(f) +
                                            " is not a number"));
}

// Splits a line without tabs on its first two runs of blanks: start, end, rest.
std::vector<std::string_view> split_on_blanks(std::string_view s) {
  std::vector<std::string_view> fields;
  s = trim(s);
  for (int i = 0; i < 2 && !s.empty(); ++i) {
    std::size_t sp = s.find_first_of(" \t");
    if (sp == std::string_view::npos) break;
    fields.push_back(s.substr(0, sp));
    s = trim(s.substr(sp));
  }
  if (!s.empty()) fields.push_back(s);
  return fields;
}

// ---------------------------------------------------------------------------------------------
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
        if (pos_ >= s_.size())
          throw Error(error_at_line(path_, t.line, "unterminated text (missing closing quote)"));
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
    while (pos_ < s_.size() && !is_blank(s_[pos_]) && s_[pos_] != '"' &&
           !(pos_ > start && s_[pos_] == '[')) {
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
  static bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
  }
  void skip_blanks() {
    while (pos_ < s_.size() && is_blank(s_[pos_])) {
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
    if (t.kind != Token::String)
      throw Error(error_at_line(path_, last_line(t), "Object class = \"TextGrid\" missing"));
    if (t.text.rfind("TextGrid", 0) != 0)
      throw Error(error_at_line(path_, t.line,
                                "object class is " + quote_field(t.text) + ", not a TextGrid"));
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
        tier.intervals.reserve(static_cast<std::size_t>(std::min(n, 1000000L)));
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
        throw Error(error_at_line(path_, cls.line, "unknown tier class " + quote_field(tier.cls) +
                                                       " (expected IntervalTier or TextTier)"));
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
      throw Error(error_at_line(path_, last_line_,
                                "unexpected end of file (truncated TextGrid?) while reading " + what));
    if (t.kind == Token::Bad || t.kind == Token::Label) {
      std::string lower = ascii_lower(t.text);
      if (!lower.empty() && (lower.front() == '+' || lower.front() == '-')) lower.erase(0, 1);
      bool nonfinite = lower == "nan" || lower == "inf" || lower == "infinity";
      throw Error(error_at_line(path_, t.line, "malformed value " + quote_field(t.text) + " for " + what +
                                                   (nonfinite ? " (not a finite number)"
                                                              : " (not a number)")));
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

// ---------------------------------------------------------------------------------------------
// Google JSON

using nlohmann::json;

[[noreturn]] void json_fail(const std::string& path, const std::string& where, const std::string& what) {
  throw Error(path + ": " + (where.empty() ? "" : where + ": ") + what);
}

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
      json_fail(path, w, "bad time " + quote_field(x.get_ref<const std::string&>()) +
                             " (expected seconds such as \"1.500s\")");
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

// -----------------------------------------------------------------------------------------------

TranscriptFormat parse_transcript_format(const std::string& name) {
  std::string n = ascii_lower(trim(name));
  if (n == "auto") return TranscriptFormat::Auto;
  if (n == "tsv") return TranscriptFormat::Tsv;
  if (n == "textgrid") return TranscriptFormat::TextGrid;
  if (n == "json") return TranscriptFormat::Json;
  throw Error("unknown transcript format " + quote_field(name) +
              " (expected one of: auto, tsv, textgrid, json)");
}

std::string transcript_format_name(TranscriptFormat format) {
  switch (format) {
    case TranscriptFormat::Auto: return "auto";
    case TranscriptFormat::Tsv: return "tsv";
    case TranscriptFormat::TextGrid: return "textgrid";
    case TranscriptFormat::Json: return "json";
  }
  return "auto";
}

std::vector<Word> read_transcript(const std::string& path, TranscriptFormat format) {
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
  switch (format) {
    case TranscriptFormat::Tsv: return read_tsv(path);
    case TranscriptFormat::TextGrid: return read_textgrid(path);
    case TranscriptFormat::Json: return read_google_json(path);
    case TranscriptFormat::Auto: break;
  }
  throw Error(path + ": unknown transcript format");
}

std::vector<Word> read_tsv(const std::string& path) {
  const std::string text = detail::read_text_file(path, "transcript");
  const std::vector<std::string> lines = detail::split_lines(text);
  std::vector<Word> words;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const long line = static_cast<long>(i + 1);
    std::string_view l = lines[i];
    if (trim(l).empty()) continue;
    std::vector<std::string_view> fields;
    std::size_t tab1 = l.find('\t');
    if (tab1 == std::string_view::npos) {
      fields = split_on_blanks(l);
    } else {
      fields.push_back(l.substr(0, tab1));
      std::size_t tab2 = l.find('\t', tab1 + 1);
      if (tab2 == std::string_view::npos) {
        fields.push_back(l.substr(tab1 + 1));
      } else {
        fields.push_back(l.substr(tab1 + 1, tab2 - tab1 - 1));
        fields.push_back(l.substr(tab2 + 1));
      }
    }
    if (fields.size() < 3)
      throw Error(error_at_line(path, line, "expected start<TAB>end<TAB>word, found " +
                                                std::to_string(fields.size()) + " field(s): " +
                                                quote_field(trim(l))));
    Word w;
    w.start = tsv_time(fields[0], "start", path, line);
    w.end = tsv_time(fields[1], "end", path, line);
    w.text = std::string(trim(fields[2]));
    if (w.end < w.start)
      throw Error(error_at_line(path, line, "word " + quote_field(w.text) + " ends (" +
                                                format_seconds(w.end) + " s) before it starts (" +
                                                format_seconds(w.start) + " s)"));
    if (w.text.empty()) continue;  // silence
    words.push_back(std::move(w));
  }
  sort_words(words);
  return words;
}

std::vector<Word> read_textgrid(const std::string& path) {
  const std::string text = detail::read_text_file(path, "TextGrid");
  std::vector<Tier> tiers = TextGridParser(text, path).parse();

  const Tier* chosen = nullptr;
  for (const Tier& t : tiers)
    if (ascii_lower(trim(t.name)) == "words") {
      chosen = &t;
      break;
    }
  if (!chosen) {  // e.g. Montreal Forced Aligner's "speaker - words"
    const Tier* candidate = nullptr;
    int n = 0;
    for (const Tier& t : tiers) {
      std::string name = ascii_lower(trim(t.name));
      if (name.size() > 5 && name.compare(name.size() - 5, 5, "words") == 0) {
        candidate = &t;
        ++n;
      }
    }
    if (n == 1) chosen = candidate;
  }
  if (!chosen) {
    std::string list;
    for (const Tier& t : tiers) list += (list.empty() ? "" : ", ") + quote_field(t.name);
    throw Error(path + ": no tier named \"words\" (tiers found: " +
                (list.empty() ? std::string("none") : list) + ")");
  }
  if (chosen->cls != "IntervalTier")
    throw Error(error_at_line(path, chosen->line, "the words tier " + quote_field(chosen->name) +
                                                      " is a " + chosen->cls + ", not an IntervalTier"));

  std::vector<Word> words;
  for (const Interval& iv : chosen->intervals) {
    if (iv.xmax < iv.xmin)
      throw Error(error_at_line(path, iv.line, "interval " + quote_field(iv.text) + " ends (" +
                                                   format_seconds(iv.xmax) + " s) before it starts (" +
                                                   format_seconds(iv.xmin) + " s)"));
    if (iv.xmin < 0)
      throw Error(error_at_line(path, iv.line, "interval " + quote_field(iv.text) +
                                                   " starts at a negative time " +
                                                   format_seconds(iv.xmin)));
    std::string_view t = trim(iv.text);
    if (t.empty()) continue;  // silence
    words.push_back(Word{iv.xmin, iv.xmax, std::string(t)});
  }
  sort_words(words);
  return words;
}

std::vector<Word> read_google_json(const std::string& path) {
  const std::string text = detail::read_text_file(path, "transcript");
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    if (std::size_t p = what.find("] "); p != std::string::npos && what.front() == '[')
      what = what.substr(p + 2);
    throw Error(error_at_byte(path, static_cast<long long>(e.byte), "invalid JSON: " + what));
  }

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
    json_fail(path, "", "expected a Google speech JSON: an array of results or an object with "
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
      auto word = w.find("word");
      if (!st) json_fail(path, wh, "missing \"start_time\"");
      if (!en) json_fail(path, wh, "missing \"end_time\"");
      if (word == w.end()) json_fail(path, wh, "missing \"word\"");
      if (!word->is_string()) json_fail(path, wh + ".word", "expected a string");
      Word out;
      out.start = json_time(*st, path, wh + ".start_time");
      out.end = json_time(*en, path, wh + ".end_time");
      out.text = std::string(trim(word->get_ref<const std::string&>()));
      if (out.start < 0) json_fail(path, wh, "negative start time " + format_seconds(out.start));
      if (out.end < out.start)
        json_fail(path, wh, "word " + quote_field(out.text) + " ends (" + format_seconds(out.end) +
                                " s) before it starts (" + format_seconds(out.start) + " s)");
      if (out.text.empty()) continue;
      words.push_back(std::move(out));
    }
  }
  sort_words(words);
  return words;
}

void check_transcript_fits(const std::vector<Word>& words, double duration_s,
                           const std::string& path, double tolerance_s) {
  for (const Word& w : words) {
    if (w.end > duration_s + tolerance_s)
      throw Error(path + ": the transcript runs past the end of the audio: word " + quote_field(w.text) +
                  " ends at " + format_seconds(w.end) + " s but the audio lasts " +
                  format_seconds(duration_s) + " s (a transcript of another recording?)");
  }
}

}  // namespace gmg::text
