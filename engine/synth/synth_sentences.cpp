// The synthetic speaker's sentences: a small template grammar of English (see synth.h), so the
// transcript reads as speech and the gesture keywords of assets/keywords.txt come where a
// speaker would say them ("The children found a huge garden.", "Her mother often painted those
// windows.").
//
// Every word the grammar can say is in one class below, and a class is either all keywords of
// the lexicon (with the gesture they carry) or all words the lexicon lacks; tests/synth checks
// both against the lexicon. No two neighbouring words of a sentence form a lexicon phrase ("a
// lot", "at the end"), so each keyword word is one keyword event of its own.
#include <cctype>
#include <sstream>

#include "engine/core/error.h"
#include "engine/synth/synth_internal.h"

namespace gmg::synth_internal {
namespace {

struct Vocab {
  const char* text;
  int syllables;
  int stress;  // index of the stressed syllable, -1 for none
};

struct WordClass {
  const char* name;      // as written in the templates
  SynthGesture gesture;  // None: none of the words is a keyword
  std::vector<Vocab> words;
};

// Neutral classes first, then the keyword classes by the gesture they carry.
const std::vector<WordClass>& classes() {
  static const std::vector<WordClass> all = {
      // Unstressed function words.
      {"DET", SynthGesture::None, {{"her", 1, -1}, {"his", 1, -1}}},
      {"the", SynthGesture::None, {{"the", 1, -1}}},
      {"a", SynthGesture::None, {{"a", 1, -1}}},
      {"is", SynthGesture::None, {{"is", 1, -1}}},
      {"was", SynthGesture::None, {{"was", 1, -1}}},
      {"did", SynthGesture::None, {{"did", 1, -1}}},
      {"to", SynthGesture::None, {{"to", 1, -1}}},
      {"with", SynthGesture::None, {{"with", 1, -1}}},
      {"and", SynthGesture::None, {{"and", 1, -1}}},
      {"it", SynthGesture::None, {{"it", 1, -1}}},
      // Content words: one stressed syllable each. People (after her/his/the), groups (after
      // the), names; things one makes or handles, topics one explains, places one goes to.
      {"PERSON",
       SynthGesture::None,
       {{"brother", 2, 0}, {"sister", 2, 0}, {"mother", 2, 0}, {"father", 2, 0}, {"family", 3, 0}, {"friends", 1, 0}}},
      {"GROUP",
       SynthGesture::None,
       {{"children", 2, 0},
        {"teacher", 2, 0},
        {"students", 2, 0},
        {"neighbours", 2, 0},
        {"engineers", 3, 2},
        {"doctor", 2, 0}}},
      {"NAME", SynthGesture::None, {{"Anna", 2, 0}, {"Peter", 2, 0}, {"Maria", 3, 1}, {"David", 2, 0}}},
      {"THING",
       SynthGesture::None,
       {{"garden", 2, 0},
        {"picture", 2, 0},
        {"kitchen", 2, 0},
        {"bridge", 1, 0},
        {"house", 1, 0},
        {"boat", 1, 0},
        {"table", 2, 0},
        {"window", 2, 0},
        {"computer", 3, 1}}},
      {"THINGS",
       SynthGesture::None,
       {{"houses", 2, 0},
        {"pictures", 2, 0},
        {"letters", 2, 0},
        {"bottles", 2, 0},
        {"windows", 2, 0},
        {"boxes", 2, 0}}},
      {"TOPIC",
       SynthGesture::None,
       {{"story", 2, 0},
        {"problem", 2, 0},
        {"question", 2, 0},
        {"answer", 2, 0},
        {"plan", 1, 0},
        {"music", 2, 0},
        {"idea", 3, 1}}},
      {"PLACEN",
       SynthGesture::None,
       {{"museum", 3, 1}, {"market", 2, 0}, {"river", 2, 0}, {"station", 2, 0}, {"city", 2, 0}, {"school", 1, 0}}},
      {"VMAKE",
       SynthGesture::None,
       {{"built", 1, 0},
        {"painted", 2, 0},
        {"fixed", 1, 0},
        {"bought", 1, 0},
        {"cleaned", 1, 0},
        {"found", 1, 0},
        {"sold", 1, 0},
        {"carried", 2, 0}}},
      {"VTOPIC",
       SynthGesture::None,
       {{"explained", 2, 1},
        {"liked", 1, 0},
        {"remembered", 3, 1},
        {"discovered", 3, 1},
        {"understood", 3, 2},
        {"finished", 2, 0}}},
      {"VVISIT", SynthGesture::None, {{"visited", 3, 0}, {"liked", 1, 0}, {"passed", 1, 0}, {"painted", 2, 0}}},
      {"VBASE",
       SynthGesture::None,
       {{"like", 1, 0}, {"explain", 2, 1}, {"finish", 2, 0}, {"remember", 3, 1}, {"understand", 3, 2}}},
      {"VMOVE",
       SynthGesture::None,
       {{"moved", 1, 0}, {"walked", 1, 0}, {"went", 1, 0}, {"ran", 1, 0}, {"drove", 1, 0}}},
      {"SAID", SynthGesture::None, {{"said", 1, 0}, {"thought", 1, 0}, {"knew", 1, 0}}},
      {"ADJT",
       SynthGesture::None,
       {{"beautiful", 3, 0},
        {"expensive", 3, 1},
        {"famous", 2, 0},
        {"useful", 2, 0},
        {"strange", 1, 0},
        {"old", 1, 0}}},
      {"ADJP",
       SynthGesture::None,
       {{"quiet", 2, 0}, {"crowded", 2, 0}, {"busy", 2, 0}, {"cold", 1, 0}, {"dark", 1, 0}, {"beautiful", 3, 0}}},
      // Keywords. Size and quantity, evaluation: both hands open out.
      {"SIZE",
       SynthGesture::Open,
       {{"big", 1, 0}, {"small", 1, 0}, {"huge", 1, 0}, {"tiny", 2, 0}, {"long", 1, 0}, {"wide", 1, 0}}},
      {"QUANT",
       SynthGesture::Open,
       {{"three", 1, 0}, {"two", 1, 0}, {"ten", 1, 0}, {"many", 2, 0}, {"several", 3, 0}, {"both", 1, 0}}},
      {"EVAL", SynthGesture::Open, {{"great", 1, 0}, {"good", 1, 0}, {"bad", 1, 0}, {"better", 2, 0}}},
      {"TOGETHER", SynthGesture::Open, {{"together", 3, 1}}},
      // Pointing: the dominant hand points out.
      {"DEIX", SynthGesture::Point, {{"this", 1, 0}, {"that", 1, 0}}},
      {"DEIXS", SynthGesture::Point, {{"these", 1, 0}, {"those", 1, 0}}},
      {"PLACE", SynthGesture::Point, {{"here", 1, 0}, {"there", 1, 0}, {"outside", 2, 1}, {"inside", 2, 1}}},
      {"AWAY", SynthGesture::Point, {{"away", 2, 1}, {"back", 1, 0}, {"across", 2, 1}, {"around", 2, 1}}},
      // Negation and contrast: both hands sweep out, palms down.
      {"NOT", SynthGesture::Sweep, {{"not", 1, 0}}},
      {"NEVER", SynthGesture::Sweep, {{"never", 2, 0}}},
      {"BUT", SynthGesture::Sweep, {{"but", 1, 0}, {"however", 3, 1}}},
      // Intensifiers, time and opinion: both hands lift to the chest.
      {"INTENS",
       SynthGesture::Lift,
       {{"very", 2, 0}, {"really", 2, 0}, {"absolutely", 4, 0}, {"completely", 3, 1}, {"extremely", 3, 1}}},
      {"TIME", SynthGesture::Lift, {{"then", 1, 0}, {"later", 2, 0}, {"finally", 3, 0}, {"soon", 1, 0}}},
      {"OFTEN", SynthGesture::Lift, {{"always", 2, 0}, {"often", 2, 0}, {"sometimes", 2, 0}, {"usually", 4, 0}}},
      {"AGAIN", SynthGesture::Lift, {{"again", 2, 1}, {"now", 1, 0}, {"later", 2, 0}}},
      {"MAYBE", SynthGesture::Lift, {{"maybe", 2, 0}, {"actually", 4, 0}, {"probably", 3, 0}}},
  };
  return all;
}

// The sentence templates. A token is a class name (a word drawn from it) or, for SUBJ, a subject
// ("her/his PERSON", "the GROUP" or a NAME). "?" in front: the word is said half the time; ","
// after: a short pause follows (a phrase ends inside the sentence).
const char* const kTemplates[] = {
    "SUBJ VMAKE a SIZE THING",
    "SUBJ NEVER VTOPIC the TOPIC",
    "DEIX THING is ?INTENS ADJT",
    "TIME, the GROUP VMOVE AWAY",
    "SUBJ did NOT VBASE the TOPIC",
    "BUT SUBJ VMAKE QUANT THINGS",
    "SUBJ VMAKE the THING TOGETHER",
    "SUBJ SAID the TOPIC was ?INTENS EVAL",
    "SUBJ VVISIT the PLACEN, BUT it was ?INTENS ADJP",
    "SUBJ OFTEN VMAKE DEIXS THINGS",
    "MAYBE the GROUP VMOVE PLACE AGAIN",
    "the THING was ?INTENS SIZE, and the GROUP VMAKE it",
    "SUBJ VTOPIC the TOPIC with the GROUP",
    "SUBJ VMOVE to the PLACEN and VMAKE the THINGS",
};

const WordClass& class_named(const std::string& name) {
  for (const WordClass& c : classes())
    if (name == c.name) return c;
  throw Error("synth: the sentence grammar has no word class '" + name + "'");  // a bug of the table
}

void add_word(std::vector<SentenceWord>& out, const WordClass& c, Rng& rng) {
  const Vocab& v = c.words[static_cast<std::size_t>(rng.below(static_cast<int>(c.words.size())))];
  SentenceWord w;
  w.text = v.text;
  w.syllables = v.syllables;
  w.stress = v.stress;
  w.gesture = c.gesture;
  out.push_back(w);
}

}  // namespace

std::vector<SentenceWord> make_sentence(Rng& rng) {
  const int count = static_cast<int>(sizeof(kTemplates) / sizeof(kTemplates[0]));
  std::istringstream tokens(kTemplates[rng.below(count)]);
  std::vector<SentenceWord> out;
  std::string token;
  while (tokens >> token) {
    const bool pause = token.back() == ',';
    if (pause) token.pop_back();
    const bool optional = token.front() == '?';
    if (optional) token.erase(0, 1);
    if (optional && rng.uniform() < 0.5) continue;
    if (token == "SUBJ") {
      const double r = rng.uniform();
      if (r < 0.2) {
        add_word(out, class_named("NAME"), rng);
      } else if (r < 0.6) {
        add_word(out, class_named("DET"), rng);
        add_word(out, class_named("PERSON"), rng);
      } else {
        add_word(out, class_named("the"), rng);
        add_word(out, class_named("GROUP"), rng);
      }
    } else {
      add_word(out, class_named(token), rng);
    }
    out.back().pause_after = pause;
  }
  // Written as a sentence: a capital first letter, commas, a full stop.
  std::string& first = out.front().text;
  first[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(first[0])));
  for (SentenceWord& w : out)
    if (w.pause_after) w.text += ',';
  out.back().text += '.';
  out.back().pause_after = false;
  return out;
}

std::vector<GrammarWord> grammar_vocabulary() {
  std::vector<GrammarWord> out;
  for (const WordClass& c : classes())
    for (const Vocab& v : c.words) out.push_back({v.text, c.gesture});
  return out;
}

}  // namespace gmg::synth_internal
