// The speech plan: sentences of the grammar (synth_sentences.cpp) timed as phrases, words and
// syllables with their stress (see synth.h).
#include <algorithm>

#include "engine/synth/synth_internal.h"

namespace gmg::synth_internal {
namespace {

// Appends word w starting at `start` with the given syllable lengths; returns the end of its
// last syllable.
double add_word(SpeechPlan& plan, const SentenceWord& w, double start, const std::vector<double>& lengths,
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
  plan.word_gesture.push_back(w.gesture);
  if (w.gesture != SynthGesture::None) {
    plan.keyword_times.push_back(word.start);
    plan.keyword_gestures.push_back(w.gesture);
  }
  return s_time;
}

void close_phrase(SpeechPlan& plan, std::size_t first_word, bool ends_sentence) {
  plan.phrases.push_back(SynthPhrase{plan.words[first_word].start, plan.words.back().end, ends_sentence});
}

// Says one sentence from t on, at `rate` syllables per second; returns false when it was cut at
// end_limit (or not even its first word fitted).
bool add_sentence(SpeechPlan& plan, double t, double end_limit, double rate, Rng& rng) {
  const std::vector<SentenceWord> sentence = make_sentence(rng);
  double cur = t;
  std::size_t first_word = plan.words.size();
  for (const SentenceWord& w : sentence) {
    std::vector<double> lengths;
    double word_len = 0;
    for (int s = 0; s < w.syllables; ++s) {
      lengths.push_back(round_ms(rng.uniform(0.8, 1.2) / rate));
      word_len += lengths.back();
    }
    if (cur + word_len > end_limit) {
      if (plan.words.size() > first_word) close_phrase(plan, first_word, true);
      return false;
    }
    cur = add_word(plan, w, cur, lengths, end_limit) + round_ms(rng.uniform(0.0, 0.03));  // short inter-word gap
    if (w.pause_after) {
      close_phrase(plan, first_word, false);
      first_word = plan.words.size();
      cur = round_ms(plan.phrases.back().end + rng.uniform(0.3, 0.45));
    }
  }
  close_phrase(plan, first_word, true);
  return true;
}

}  // namespace

SpeechPlan plan_speech(double duration, double style, Rng& rng) {
  SpeechPlan plan;
  const double end_limit = duration - 0.15;  // the last word ends at least 150 ms before the end
  double t = rng.uniform(0.4, 0.9);          // lead-in silence
  while (t + 0.6 <= end_limit) {
    const double rate = std::clamp(4.3 + 0.7 * style + rng.uniform(-0.25, 0.25), 4.0, 5.2);
    if (!add_sentence(plan, t, end_limit, rate, rng)) break;
    // Between sentences the hands go back to rest: most pauses are long enough for them to
    // sink and rise again, a third of them long enough to stay at rest for a while.
    t = plan.phrases.back().end + (rng.uniform() < 0.35 ? rng.uniform(1.6, 2.4) : rng.uniform(0.8, 1.2));
  }
  return plan;
}

}  // namespace gmg::synth_internal
