// Internal helpers of the text module: reading a text file into UTF-8, splitting lines,
// parsing numbers. Not part of the public API (namespace gmg::text::detail).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace gmg::text::detail {

// Reads the whole file `path` and returns its text as UTF-8:
// - a UTF-8 byte-order mark is removed;
// - UTF-16LE / UTF-16BE with a byte-order mark (as Praat often writes) is decoded to UTF-8;
//   UTF-16LE without a mark is recognised when the first code unit is ASCII (a NUL second byte);
//   an unpaired surrogate becomes U+FFFD.
// Throws gmg::Error naming the file (and `what`, e.g. "transcript") when it cannot be opened
// or read, or when UTF-16 data has an odd number of bytes.
std::string read_text_file(const std::string& path, const std::string& what);

// Decodes raw file bytes as described above (exposed for tests of the decoder).
// Throws gmg::Error naming `path` on an odd UTF-16 byte count.
std::string decode_to_utf8(const std::string& bytes, const std::string& path);

// Splits text into lines on "\n", removing a trailing "\r" of each line (CRLF files).
// A final line without "\n" is kept; a final empty line after the last "\n" is not.
std::vector<std::string> split_lines(const std::string& text);

// Removes leading and trailing ASCII whitespace (space, tab, CR, LF, FF, VT).
std::string_view trim(std::string_view s);

// Parses a whole field (after trimming) as a finite decimal number ("1.5", "-2", "+3e-1",
// ".5"), locale-independently. Returns nullopt for an empty field, trailing garbage,
// NaN or infinity.
std::optional<double> parse_number(std::string_view field);

// ASCII lower case of s (other bytes unchanged).
std::string ascii_lower(std::string_view s);

}  // namespace gmg::text::detail
