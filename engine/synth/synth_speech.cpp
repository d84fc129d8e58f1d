// The speech plan: phrases of words, each word's syllables with their stress (see synth.h).
#include <algorithm>

#include "engine/synth/synth_internal.h"

namespace gmg::synth_internal {
namespace {

struct VocabWord {
  const char* text;
  int syllables;
  int stress;  // index of the stressed syllable, -1 for none
};

// Gesture keywords: every one of them is in assets/keywords.txt.
const VocabWord kKeywords[] = {
    {"this", 1, 0},  {"big", 1, 0},  {"not", 1, 0},    {"very", 2, 0},   {"all", 1, 0},
    {"never", 2, 0}, {"here", 1, 0}, {"really", 2, 0}, {"always", 2, 0}, {"together", 3, 1},
};
// Neutral content words: none of them is in the lexicon.
const VocabWord kContent[] = {
    {"people", 2, 0},   {"water", 2, 0},  {"music", 2, 0},   {"story", 2, 0},  {"city", 2, 0},   {"problem", 2, 0},
    {"question", 2, 0}, {"paper", 2, 0},  {"money", 2, 0},   {"garden", 2, 0}, {"family", 3, 0}, {"computer", 3, 1},
    {"animal", 3, 0},   {"energy", 3, 0}, {"company", 3, 0}, {"banana", 3, 1}, {"house", 1, 0},  {"work", 1, 0},
    {"car", 1, 0},      {"made", 1, 0},   {"said", 1, 0},    {"book", 1, 0},   {"friend", 1, 0}, {"school", 1, 0},
    {"game", 1, 0},     {"road", 1, 0},   {"food", 1, 0},    {"world", 1, 0},  {"town", 1, 0},   {"dog", 1, 0},
};
// Unstressed function words: none of them is in the lexicon, and none starts a lexicon phrase
// together with the words above.
const VocabWord kFunction[] = {
    {"the", 1, -1}, {"and", 1, -1}, {"is", 1, -1},   {"to", 1, -1},   {"of", 1, -1},
    {"it", 1, -1},  {"was", 1, -1}, {"with", 1, -1}, {"from", 1, -1},
};
template <typename T, std::size_t N>
constexpr int count_of(const T (&)[N]) {
  return static_cast<int>(N);
}

enum class WordKind { Content, Function, Keyword };

// A function word ~30% (never two in a row), a keyword ~15% (never two in a row, so every
// keyword is its own keyword event and gesture), otherwise a content word.
const VocabWord& pick_word(Rng& rng, WordKind previous, WordKind* kind) {
  const double r = rng.uniform();
  if (r < 0.17 && previous != WordKind::Keyword)
    *kind = WordKind::Keyword;
  else if (r < 0.17 + 0.30 && previous != WordKind::Function)
    *kind = WordKind::Function;
  else
    *kind = WordKind::Content;
  switch (*kind) {
    case WordKind::Keyword:
      return kKeywords[rng.below(count_of(kKeywords))];
    case WordKind::Function:
      return kFunction[rng.below(count_of(kFunction))];
    default:
      return kContent[rng.below(count_of(kContent))];
  }
}

// Appends word w starting at `start` with the given syllable lengths; returns the end of its
// last syllable.
double add_word(SpeechPlan& plan, const VocabWord& w, WordKind kind, double start, const std::vector<double>& lengths,
                double end_limit) {
  const int word_index = static_cast<int>(plan.words.size());
  double s_time = round_ms(start);
  for (int s = 0; s < w.syllables; ++s) {
    SynthSyllable syl;
    syl.time = s_time;
    syl.stressed = s == w.stress;
    syl.word = word_index;
    plan.syllables.push_back(syl);
    s_time = round_ms(s_time + lengths[static_cast<std::size_t>(s)]);
  }
  text::Word word;
  word.start = round_ms(start);
  word.end = std::min(round_ms(s_time - 0.02), round_ms(end_limit));  // ends as its last syllable fades
  word.text = w.text;
  plan.words.push_back(word);
  plan.word_is_keyword.push_back(kind == WordKind::Keyword);
  if (kind == WordKind::Keyword) plan.keyword_times.push_back(word.start);
  return s_time;
}

// Fills one phrase starting at t with words until target_end (or end_limit); returns false when
// not even one word fits. *previous is the kind of the last word placed.
bool add_phrase(SpeechPlan& plan, double t, double target_end, double end_limit, double rate, Rng& rng,
                WordKind* previous) {
  double cur = t;
  const std::size_t first_word = plan.words.size();
  for (;;) {
    WordKind kind;
    const VocabWord& w = pick_word(rng, *previous, &kind);
    std::vector<double> lengths;
    double word_len = 0;
    for (int s = 0; s < w.syllables; ++s) {
      lengths.push_back(round_ms(rng.uniform(0.8, 1.2) / rate));
      word_len += lengths.back();
    }
    const bool have_words = plan.words.size() > first_word;
    if (cur + word_len > end_limit) break;
    if (have_words && cur + word_len > target_end) break;
    const double s_time = add_word(plan, w, kind, cur, lengths, end_limit);
    *previous = kind;
    cur = s_time + round_ms(rng.uniform(0.0, 0.03));  // short inter-word gap
  }
  if (plan.words.size() == first_word) return false;
  plan.phrases.push_back(SynthPhrase{plan.words[first_word].start, plan.words.back().end});
  return true;
}

}  // namespace

SpeechPlan plan_speech(double duration, double style, Rng& rng) {
  SpeechPlan plan;
  const double end_limit = duration - 0.15;  // the last word ends at least 150 ms before the end
  double t = rng.uniform(0.4, 0.9);          // lead-in silence
  WordKind previous = WordKind::Content;
  while (t + 0.6 <= end_limit) {
    const double target_end = std::min(t + rng.uniform(1.5, 4.0), end_limit);
    const double rate = std::clamp(4.3 + 0.7 * style + rng.uniform(-0.25, 0.25), 4.0, 5.2);
    if (!add_phrase(plan, t, target_end, end_limit, rate, rng, &previous)) break;
    previous = WordKind::Function;  // so the next phrase opens with a content word or a keyword
    t = plan.phrases.back().end + rng.uniform(0.3, 0.8);
  }
  return plan;
}

}  // namespace gmg::synth_internal
