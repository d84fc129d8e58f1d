// Small text utilities shared by every module: one copy of each.
//
// All of them are byte-oriented and locale-independent: "lower case" and "white space" mean
// ASCII only, so UTF-8 text passes through unchanged.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace gmg {

// True for ASCII white space: space, tab, CR, LF, FF, VT (what trim removes and the tokenizers
// of the readers split on).
inline bool is_ascii_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

// Removes leading and trailing ASCII white space (is_ascii_space).
std::string_view trim(std::string_view s);

// ASCII lower case of s (other bytes unchanged).
std::string ascii_lower(std::string_view s);

// True when s ends with suffix, comparing ASCII letters case-insensitively.
bool ends_with_ci(std::string_view s, std::string_view suffix);

// Splits on `separator`, trims every piece and drops the empty ones: "a, b,,c " -> {a, b, c}.
std::vector<std::string> split_trimmed(std::string_view s, char separator);

// Splits text into lines on "\n", removing a trailing "\r" of each line (CRLF files). A final
// line without "\n" is kept; a final empty line after the last "\n" is not.
std::vector<std::string> split_lines(const std::string& text);

// True when the text starts with the UTF-8 byte-order mark EF BB BF (all three bytes).
bool has_utf8_bom(std::string_view s);

// s without a leading UTF-8 byte-order mark (unchanged when it has none).
std::string_view strip_utf8_bom(std::string_view s);

// Parses a whole field (after trimming) as a finite decimal number ("1.5", "-2", "+3e-1", ".5"),
// locale-independently. nullopt for an empty field, trailing garbage, NaN or infinity.
std::optional<double> parse_number(std::string_view field);

// The shortest text that reads back as exactly v ("0.2", "1e-05", "20231009", "100" rather than
// "1e+02"; plain digits win ties); "nan"/"inf" as such. Used wherever a number is printed for a
// human or a config file.
std::string format_number(double v);

// Writes v as printf's "%.6f" in the C locale would (correctly rounded, ties to even), except that
// a value that rounds to zero is written "0.000000" whatever its sign; returns the end of the text
// (not terminated). `out` must hold kFixed6Chars characters. The common values (|v| < 1e6) are
// formatted from one rounded integer; the rest, and the few within 2^-12 of a rounding tie, by
// std::to_chars. Writing a motion's values is most of writing a BVH file.
inline constexpr std::size_t kFixed6Chars = 400;  // the longest finite double in "%.6f" is 317
char* format_fixed6(double v, char* out);

// One character of UTF-8 text: its code point and how many bytes encode it (1 to 4).
struct Utf8Char {
  char32_t code_point = 0;
  std::size_t length = 0;
};

// The character whose encoding starts at s[pos], decoded strictly (RFC 3629: the shortest form
// only, no surrogates U+D800..U+DFFF, nothing above U+10FFFF); nullopt when the bytes there do not
// start a well-formed character: a stray continuation byte, an overlong form, a surrogate, a
// value beyond U+10FFFF, a sequence cut short by the end of s or by a byte that does not continue
// it, or pos at or past the end. The one UTF-8 decoder of the engine: what it rejects, every
// caller treats byte by byte.
std::optional<Utf8Char> decode_utf8(std::string_view s, std::size_t pos);

// Valid UTF-8 copy of s: every byte that does not start a well-formed UTF-8 sequence
// (decode_utf8, so also overlong forms and surrogates) becomes U+FFFD. Text headed for JSON goes through this so a
// Latin-1 file name can never make a writer throw.
std::string to_valid_utf8(std::string_view s);

// s with every byte a terminal could act on or mis-show written as an escape, so a message that
// quotes a file's bytes (a binary file given as a BVH) prints as one readable line: control
// characters as \n, \r, \t or \xNN, DEL and bytes that do not start well-formed UTF-8
// (decode_utf8) as \xNN, the C1 controls U+0080..U+009F as \u0080..\u009f, a backslash as
// itself. Printable ASCII and well-formed UTF-8 text stay as they are.
std::string escape_nonprintable(std::string_view s);

// s when it is at most `max_bytes` long, else its first max_bytes bytes (cut back to the start of
// a UTF-8 character) and "…": a value quoted in a message stays one readable line, however long
// the input that holds it (a 10 MB key of a config file).
std::string shorten_for_message(std::string_view s, std::size_t max_bytes = 60);

// The optimal-string-alignment distance of a and b: insertions, deletions, substitutions and
// swaps of two neighbouring characters each count 1 ("biuld" is 1 from "build"). Byte-wise.
std::size_t edit_distance(std::string_view a, std::string_view b);

// The name of `names` nearest to `word` (edit_distance of their ASCII lower case) when it is a
// plausible typo: at most 2 edits, and fewer than half of word's length (so "-x" suggests
// nothing); the first of equally near names. nullopt when none is, or when word is one of names.
// Names whose length differs from word's by more than 2 are not compared (they cannot be near),
// so the time is linear in a long word's length.
std::optional<std::string> nearest_name(std::string_view word, const std::vector<std::string>& names);

// " (did you mean 'build'?)" for nearest_name(word, names), or "" when there is none: the tail
// of every "unknown ..." message.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& names);

}  // namespace gmg
