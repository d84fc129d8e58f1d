// GENEA TSV transcripts: start<TAB>end<TAB>word, one word a line.
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "text/text_file.h"
#include "text/transcript.h"
#include "text/transcript_util.h"

namespace gmg::text {

using detail::format_seconds;
using detail::quote_field;
using detail::sort_words;

namespace {

double tsv_time(std::string_view field, const char* which, const std::string& path, long line) {
  std::string_view f = trim(field);
  if (auto v = parse_number(f)) {
    if (*v < 0) throw Error(error_at_line(path, line, std::string("negative ") + which + " time " + std::string(f)));
    return *v;
  }
  if (detail::names_non_finite(f))
    throw Error(error_at_line(path, line, std::string(which) + " time " + quote_field(f) + " is not a finite number"));
  throw Error(error_at_line(path, line, std::string(which) + " time " + quote_field(f) + " is not a number"));
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

}  // namespace

std::vector<Word> read_tsv(const std::string& path) { return parse_tsv(read_file_bytes(path), path); }

std::vector<Word> parse_tsv(const std::string& bytes, const std::string& path) {
  const std::vector<std::string> lines = split_lines(detail::decode_to_utf8(bytes, path));
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
      throw Error(error_at_line(path, line,
                                "expected start<TAB>end<TAB>word, found " + std::to_string(fields.size()) +
                                    " field(s): " + quote_field(trim(l))));
    Word w;
    w.start = tsv_time(fields[0], "start", path, line);
    w.end = tsv_time(fields[1], "end", path, line);
    w.text = std::string(trim(fields[2]));
    if (w.end < w.start)
      throw Error(error_at_line(path, line,
                                "word " + quote_field(w.text) + " ends (" + format_seconds(w.end) +
                                    " s) before it starts (" + format_seconds(w.start) + " s)"));
    if (w.text.empty()) continue;  // silence
    words.push_back(std::move(w));
  }
  sort_words(words);
  return words;
}

}  // namespace gmg::text
