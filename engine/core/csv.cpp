#include "engine/core/csv.h"

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"

namespace gmg {
namespace {

// Reads one row starting at text[i] (not a skipped line); advances i past its line end and
// `line` past the lines it spans.
CsvRow parse_row(std::string_view text, std::size_t& i, long& line, const std::string& path) {
  CsvRow row;
  row.line = line;
  std::string field;
  bool quoted = false, in_quotes = false;
  auto finish_field = [&] {
    row.fields.push_back(quoted ? field : std::string(trim(field)));
    field.clear();
    quoted = false;
  };
  while (i < text.size()) {
    const char c = text[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        i += 2;
        continue;
      }
      if (c == '"') {
        in_quotes = false;
      } else {
        if (c == '\n') ++line;
        field += c;
      }
      ++i;
      continue;
    }
    if (c == '"' && !quoted && trim(field).empty()) {
      field.clear();  // white space before an opening quote is not part of the field
      quoted = in_quotes = true;
    } else if (c == ',') {
      finish_field();
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      ++i;
      ++line;
      finish_field();
      return row;
    } else if (!quoted) {
      field += c;  // after a closing quote, everything up to the comma is dropped
    }
    ++i;
  }
  if (in_quotes) throw Error(error_at_line(path, row.line, "unterminated quoted field"));
  finish_field();
  return row;
}

}  // namespace

std::vector<CsvRow> csv_parse(std::string_view text, const std::string& path) {
  std::vector<CsvRow> rows;
  std::size_t i = has_utf8_bom(text) ? 3 : 0;
  long line = 1;
  while (i < text.size()) {
    if (text[i] == '#' || text[i] == '\n' || text[i] == '\r') {  // a comment or blank line
      while (i < text.size() && text[i] != '\n') ++i;
      if (i < text.size()) ++i;
      ++line;
      continue;
    }
    rows.push_back(parse_row(text, i, line, path));
  }
  return rows;
}

std::vector<CsvRow> csv_read_file(const std::string& path) { return csv_parse(read_file_bytes(path), path); }

std::string csv_field(std::string_view s) {
  const bool plain =
      s.find_first_of(",\"\n\r") == std::string_view::npos && (s.empty() || (s.front() != ' ' && s.back() != ' '));
  if (plain) return std::string(s);
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string out;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i) out += ',';
    out += csv_field(fields[i]);
  }
  return out + "\n";
}

}  // namespace gmg
