// Phone-level transcripts: the phones tier forced aligners write beside the words (BEAT2's
// TextGrids, the Montreal Forced Aligner's "speaker - phones"), in ARPAbet, and the mouth shapes
// (visemes) the face track matches them by.
//
// A phone's symbol is its ARPAbet label in upper case without the stress digit ("AH0" -> "AH");
// silence ("", "sil", "sp", "spn") has no phone: the gaps between phones are silence.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/enum_names.h"
#include "text/transcript.h"

namespace gmg::text {

struct Phone {
  double start = 0;    // seconds, finite, >= 0
  double end = 0;      // seconds, finite, >= start
  std::string symbol;  // phone_symbol of the label: never empty
};

// "AH0" -> "AH", "sil" -> "" (silence): upper case, the trailing stress digits dropped, and the
// aligners' silence and noise labels ("sil", "sp", "spn", "<eps>") empty.
std::string phone_symbol(std::string_view label);

// The phones of a transcript file: the TextGrid tier named "phones" (ASCII case-insensitive), else
// the one tier whose name ends in "phones" (MFA's "speaker - phones"); sorted by start, silence
// dropped. Empty for a transcript of another format or a TextGrid without such a tier: phones
// are optional, and the words are read as before. Errors (from the TextGrid reader) name the file
// and line.
std::vector<Phone> read_phones(const std::string& path, TranscriptFormat format = TranscriptFormat::Auto);

// Throws gmg::Error naming `path` when some phone ends after duration_s + tolerance_s: the phones
// tier runs past the end of the audio (as text/transcript.h check_transcript_fits for the words).
void check_phones_fit(const std::vector<Phone>& phones, double duration_s, const std::string& path,
                      double tolerance_s = 0.05);
std::vector<Phone> parse_textgrid_phones(const std::string& bytes, const std::string& name);

// Mouth-shape classes of ARPAbet phones, as visual speech synthesis groups them: phones of one
// class look alike on the face (p, b and m all close the lips).
enum class Viseme : std::uint8_t {
  Silence,       // no phone
  Bilabial,      // P B M: lips closed
  Labiodental,   // F V
  Dental,        // TH DH
  Alveolar,      // T D N S Z L
  Postalveolar,  // SH ZH CH JH
  Velar,         // K G NG HH
  Rhotic,        // R ER
  Rounded,       // W UW UH OW OY
  OpenVowel,     // AA AE AH AO AW AY: the jaw open
  MidVowel,      // EH EY
  CloseVowel,    // IH IY Y
  Other,         // a symbol outside ARPAbet
};
inline constexpr int kVisemeCount = 13;
inline constexpr EnumName<Viseme> kVisemeNames[] = {
    {Viseme::Silence, "silence"},      {Viseme::Bilabial, "bilabial"},  {Viseme::Labiodental, "labiodental"},
    {Viseme::Dental, "dental"},        {Viseme::Alveolar, "alveolar"},  {Viseme::Postalveolar, "postalveolar"},
    {Viseme::Velar, "velar"},          {Viseme::Rhotic, "rhotic"},      {Viseme::Rounded, "rounded"},
    {Viseme::OpenVowel, "open vowel"}, {Viseme::MidVowel, "mid vowel"}, {Viseme::CloseVowel, "close vowel"},
    {Viseme::Other, "other"}};

Viseme viseme_of(std::string_view symbol);

// Whether two phones' symbols are alike: 0 the same symbol, 1 the same viseme, 2 otherwise.
int phone_difference(std::string_view a, std::string_view b);

}  // namespace gmg::text
