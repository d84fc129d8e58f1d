#include "engine/core/strings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace gmg {

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_ascii_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_ascii_space(s.back())) s.remove_suffix(1);
  return s;
}

std::string ascii_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

bool ends_with_ci(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && ascii_lower(s.substr(s.size() - suffix.size())) == ascii_lower(suffix);
}

std::vector<std::string> split_trimmed(std::string_view s, char separator) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos <= s.size()) {
    std::size_t end = s.find(separator, pos);
    if (end == std::string_view::npos) end = s.size();
    const std::string_view piece = trim(s.substr(pos, end - pos));
    if (!piece.empty()) out.emplace_back(piece);
    pos = end + 1;
  }
  return out;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t nl = text.find('\n', pos);
    const std::size_t end = nl == std::string::npos ? text.size() : nl;
    std::size_t len = end - pos;
    if (len > 0 && text[pos + len - 1] == '\r') --len;
    lines.emplace_back(text, pos, len);
    if (nl == std::string::npos) break;
    pos = nl + 1;
  }
  return lines;
}

bool has_utf8_bom(std::string_view s) {
  return s.size() >= 3 && static_cast<unsigned char>(s[0]) == 0xEF && static_cast<unsigned char>(s[1]) == 0xBB &&
         static_cast<unsigned char>(s[2]) == 0xBF;
}

std::string_view strip_utf8_bom(std::string_view s) { return has_utf8_bom(s) ? s.substr(3) : s; }

std::optional<double> parse_number(std::string_view field) {
  field = trim(field);
  if (!field.empty() && field.front() == '+') {
    field.remove_prefix(1);
    if (!field.empty() && (field.front() == '-' || field.front() == '+')) return std::nullopt;
  }
  if (field.empty()) return std::nullopt;
  double value = 0;
  const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (ec != std::errc() || ptr != field.data() + field.size()) return std::nullopt;
  if (!std::isfinite(value)) return std::nullopt;
  return value;
}

std::string format_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  // The shortest %.{p}g that reads back exactly (p <= 17 always does, for IEEE doubles).
  char buf[32];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    double back = 0;
    const auto r = std::from_chars(buf, buf + std::char_traits<char>::length(buf), back);
    if (r.ec == std::errc() && back == v) break;
  }
  // %g writes 100 as "1e+02" (it reads back); a whole number's own digits win when not longer.
  std::string out = buf;
  if (v == std::floor(v) && std::abs(v) < 1e16) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
    if (std::char_traits<char>::length(buf) <= out.size()) out = buf;
  }
  return out;
}

char* format_fixed6(double v, char* out) {
  // v * 1e6 rounded to the nearest integer is the six-decimal text's digits. The product p is
  // rounded once: for |p| < 2^40 its error is at most 2^-13, so when p lies farther than 2^-12
  // from a half-integer, the exact product rounds to the same integer as p. Near a tie, or beyond
  // 1e6 (and for NaN and infinities), the library decides.
  const double p = v * 1e6;
  if (!(std::abs(p) < 1e12)) return std::to_chars(out, out + kFixed6Chars, v, std::chars_format::fixed, 6).ptr;
  const double q = std::nearbyint(p);
  if (0.5 - std::abs(p - q) <= 0x1p-12) {
    char* end = std::to_chars(out, out + kFixed6Chars, v, std::chars_format::fixed, 6).ptr;
    if (std::string_view(out, static_cast<std::size_t>(end - out)) == "-0.000000") {
      const std::string_view zero = "0.000000";  // the text, not a C string: no terminator
      return std::copy(zero.begin(), zero.end(), out);
    }
    return end;
  }
  auto digits = static_cast<std::int64_t>(q);
  if (digits < 0) {
    *out++ = '-';
    digits = -digits;
  }
  const auto whole = static_cast<std::uint64_t>(digits / 1000000);
  auto fraction = static_cast<std::uint32_t>(digits % 1000000);
  out = std::to_chars(out, out + 20, whole).ptr;
  *out++ = '.';
  for (int i = 5; i >= 0; --i) {
    out[i] = static_cast<char>('0' + fraction % 10);
    fraction /= 10;
  }
  return out + 6;
}

std::optional<Utf8Char> decode_utf8(std::string_view s, std::size_t pos) {
  if (pos >= s.size()) return std::nullopt;
  auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(pos);
  if (c < 0x80) return Utf8Char{c, 1};
  std::size_t len = 0;
  char32_t cp = 0;
  unsigned lo = 0x80, hi = 0xBF;  // the allowed range of the second byte
  if (c >= 0xC2 && c <= 0xDF) {   // C0 and C1 could only start overlong forms
    len = 2;
    cp = c & 0x1Fu;
  } else if (c >= 0xE0 && c <= 0xEF) {
    len = 3;
    cp = c & 0x0Fu;
    if (c == 0xE0) lo = 0xA0;  // below: overlong
    if (c == 0xED) hi = 0x9F;  // above: surrogates
  } else if (c >= 0xF0 && c <= 0xF4) {
    len = 4;
    cp = c & 0x07u;
    if (c == 0xF0) lo = 0x90;  // below: overlong
    if (c == 0xF4) hi = 0x8F;  // above: beyond U+10FFFF
  } else {
    return std::nullopt;  // a continuation byte, or F5..FF
  }
  if (pos + len > s.size()) return std::nullopt;
  for (std::size_t k = 1; k < len; ++k) {
    const unsigned b = byte(pos + k);
    if (k == 1 ? (b < lo || b > hi) : (b < 0x80 || b > 0xBF)) return std::nullopt;
    cp = (cp << 6) | (b & 0x3Fu);
  }
  return Utf8Char{cp, len};
}

std::string to_valid_utf8(std::string_view s) {
  static const char kReplacement[] = "\xEF\xBF\xBD";
  std::string out;
  out.reserve(s.size());
  std::size_t i = 0;
  while (i < s.size()) {
    if (const std::optional<Utf8Char> c = decode_utf8(s, i)) {
      out.append(s.substr(i, c->length));
      i += c->length;
    } else {
      out += kReplacement;
      ++i;
    }
  }
  return out;
}

std::string escape_nonprintable(std::string_view s) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  out.reserve(s.size());
  std::size_t pos = 0;
  while (pos < s.size()) {
    const auto c = static_cast<unsigned char>(s[pos]);
    if (c >= 0x20 && c < 0x7F) {
      out += static_cast<char>(c);
      ++pos;
      continue;
    }
    if (c == '\n' || c == '\r' || c == '\t') {
      out += c == '\n' ? "\\n" : c == '\r' ? "\\r" : "\\t";
      ++pos;
      continue;
    }
    const std::optional<Utf8Char> u = c >= 0x80 ? decode_utf8(s, pos) : std::nullopt;
    if (u && u->code_point >= 0xA0) {
      out.append(s.substr(pos, u->length));
      pos += u->length;
    } else if (u) {  // a C1 control: terminals take U+009B as the start of an escape sequence
      out += "\\u00";
      out += kHex[(u->code_point >> 4) & 0xF];
      out += kHex[u->code_point & 0xF];
      pos += u->length;
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 0xF];
      ++pos;
    }
  }
  return out;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Three rows of the dynamic programme: the swap looks two rows back.
  std::vector<std::size_t> before(b.size() + 1), previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        current[j] = std::min(current[j], before[j - 2] + 1);
    }
    before.swap(previous);
    previous.swap(current);
  }
  return previous[b.size()];
}

std::optional<std::string> nearest_name(std::string_view word, const std::vector<std::string>& names) {
  const std::string lower = ascii_lower(word);
  std::optional<std::string> best;
  std::size_t best_distance = 3;
  for (const std::string& name : names) {
    if (name == word) return std::nullopt;
    const std::size_t longer = std::max(name.size(), word.size()), shorter = std::min(name.size(), word.size());
    if (longer - shorter >= best_distance) continue;  // the distance is at least the difference in length
    const std::size_t d = edit_distance(lower, ascii_lower(name));
    if (d < best_distance && 2 * d < word.size()) {
      best = name;
      best_distance = d;
    }
  }
  return best;
}

std::string did_you_mean(std::string_view word, const std::vector<std::string>& names) {
  const std::optional<std::string> near = nearest_name(word, names);
  return near ? " (did you mean '" + *near + "'?)" : std::string();
}

std::string shorten_for_message(std::string_view s, std::size_t max_bytes) {
  if (s.size() <= max_bytes) return std::string(s);
  std::size_t cut = max_bytes;
  while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;  // a continuation byte
  return std::string(s.substr(0, cut)) + "\u2026";
}

}  // namespace gmg
