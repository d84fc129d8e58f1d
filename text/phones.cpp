// Phone symbols, the phones tier of a transcript, and the visemes of ARPAbet phones.
#include "text/phones.h"

#include <filesystem>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "text/transcript_util.h"

namespace gmg::text {

std::string phone_symbol(std::string_view label) {
  std::string s(trim(label));
  for (char& c : s)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  while (!s.empty() && s.back() >= '0' && s.back() <= '9') s.pop_back();
  if (s == "SIL" || s == "SP" || s == "SPN" || s == "<EPS>" || s == "<SIL>") s.clear();
  return s;
}

std::vector<Phone> read_phones(const std::string& path, TranscriptFormat format) {
  const bool textgrid = format == TranscriptFormat::TextGrid ||
                        (format == TranscriptFormat::Auto &&
                         ascii_lower(std::filesystem::path(path).extension().string()) == ".textgrid");
  if (!textgrid) return {};
  return parse_textgrid_phones(read_file_bytes(path), path);
}

namespace {

struct VisemeOf {
  const char* symbol;
  Viseme viseme;
};

// ARPAbet's 39 phones (CMUdict), by mouth shape.
constexpr VisemeOf kVisemes[] = {
    {"P", Viseme::Bilabial},      {"B", Viseme::Bilabial},      {"M", Viseme::Bilabial},
    {"F", Viseme::Labiodental},   {"V", Viseme::Labiodental},   {"TH", Viseme::Dental},
    {"DH", Viseme::Dental},       {"T", Viseme::Alveolar},      {"D", Viseme::Alveolar},
    {"N", Viseme::Alveolar},      {"S", Viseme::Alveolar},      {"Z", Viseme::Alveolar},
    {"L", Viseme::Alveolar},      {"SH", Viseme::Postalveolar}, {"ZH", Viseme::Postalveolar},
    {"CH", Viseme::Postalveolar}, {"JH", Viseme::Postalveolar}, {"K", Viseme::Velar},
    {"G", Viseme::Velar},         {"NG", Viseme::Velar},        {"HH", Viseme::Velar},
    {"R", Viseme::Rhotic},        {"ER", Viseme::Rhotic},       {"W", Viseme::Rounded},
    {"UW", Viseme::Rounded},      {"UH", Viseme::Rounded},      {"OW", Viseme::Rounded},
    {"OY", Viseme::Rounded},      {"AA", Viseme::OpenVowel},    {"AE", Viseme::OpenVowel},
    {"AH", Viseme::OpenVowel},    {"AO", Viseme::OpenVowel},    {"AW", Viseme::OpenVowel},
    {"AY", Viseme::OpenVowel},    {"EH", Viseme::MidVowel},     {"EY", Viseme::MidVowel},
    {"IH", Viseme::CloseVowel},   {"IY", Viseme::CloseVowel},   {"Y", Viseme::CloseVowel},
};

}  // namespace

Viseme viseme_of(std::string_view symbol) {
  if (symbol.empty()) return Viseme::Silence;
  for (const VisemeOf& v : kVisemes)
    if (symbol == v.symbol) return v.viseme;
  return Viseme::Other;
}

int phone_difference(std::string_view a, std::string_view b) {
  if (a == b) return 0;
  return viseme_of(a) == viseme_of(b) ? 1 : 2;
}

void check_phones_fit(const std::vector<Phone>& phones, double duration_s, const std::string& path,
                      double tolerance_s) {
  for (const Phone& p : phones)
    if (p.end > duration_s + tolerance_s)
      throw Error(path + ": the phones tier runs past the end of the audio: phone " + detail::quote_field(p.symbol) +
                  " ends at " + detail::format_seconds(p.end) + " s but the audio lasts " +
                  detail::format_seconds(duration_s) + " s (a transcript of another recording?)");
}

}  // namespace gmg::text
