// Internal helper of the text module: reading a text file into UTF-8, whatever encoding a
// transcript or lexicon tool wrote it in. Not part of the public API (namespace
// gmg::text::detail). Generic string helpers (trim, split_lines, parse_number, ...) are in
// engine/core/strings.h.
#pragma once

#include <string>

namespace gmg::text::detail {

// Reads the whole file `path` (engine/core/files.h read_file_bytes) and returns its text as UTF-8:
// - a UTF-8 byte-order mark is removed;
// - UTF-16LE / UTF-16BE with a byte-order mark (as Praat often writes) is decoded to UTF-8;
//   UTF-16LE without a mark is recognised when the first code unit is ASCII (a NUL second byte);
//   an unpaired surrogate becomes U+FFFD.
// Throws gmg::Error naming the file: the reader's "path: cannot open (reason)" and the like, or
// "path: UTF-16 text with an odd number of bytes (truncated file?)".
std::string read_text_file(const std::string& path);

// Decodes raw file bytes as described above (exposed for tests of the decoder).
// Throws gmg::Error naming `path` on an odd UTF-16 byte count.
std::string decode_to_utf8(const std::string& bytes, const std::string& path);

}  // namespace gmg::text::detail
