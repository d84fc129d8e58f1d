// CSV reading and writing (an RFC 4180 subset), for the batch manifests and records.
//
// Reading: comma-separated fields; a field may be "quoted" (then it may hold commas, line breaks
// and "" for a quote); LF or CRLF line ends; a UTF-8 byte-order mark at the start is skipped;
// blank lines and lines starting with '#' are skipped (manifests are written by hand). Unquoted
// fields are trimmed of ASCII white space, quoted ones are kept as written; text after a closing
// quote up to the next comma is ignored.
// Writing: a field is quoted only when it must be (a comma, quote or line break in it, or a
// leading/trailing space that a reader would trim), so plain records stay plain.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace gmg {

struct CsvRow {
  long line = 0;                    // 1-based line where the row starts (for messages)
  std::vector<std::string> fields;  // at least one (a row "" has one empty field)
};

// Rows of CSV text. `path` only names the text in errors: an unterminated quoted field throws
// gmg::Error "path: line N: unterminated quoted field", N being the line where its row starts.
std::vector<CsvRow> csv_parse(std::string_view text, const std::string& path);

// csv_parse of a file's bytes (gmg::Error naming the file when it cannot be read).
std::vector<CsvRow> csv_read_file(const std::string& path);

// One field as written: quoted with "" escapes when needed, else as is.
std::string csv_field(std::string_view s);

// A record: the fields joined by commas, ending with "\n".
std::string csv_line(const std::vector<std::string>& fields);

}  // namespace gmg
