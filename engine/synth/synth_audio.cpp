// The speech audio: one voiced burst per syllable of the plan over background noise (see synth.h).
#include <algorithm>

#include "engine/synth/synth_internal.h"

namespace gmg::synth_internal {
namespace {

// The sound of one syllable.
struct Burst {
  double amp = 0, decay = 0, tau = 0, f0 = 0, glide = 0, consonant_amp = 0;
  double length = 0;  // seconds
  int harmonics = 1;
  double norm = 1;  // sum of the harmonics' amplitudes 1/k
  static constexpr double kAttack = 0.010, kConsonantLen = 0.012, kFade = 0.005;
};

// Draws syllable i's burst. `progress` is its position in its phrase (0..1): the pitch falls
// over a phrase.
Burst draw_burst(const SpeechPlan& plan, std::size_t i, double progress, double f0_speaker, double sr, Rng& rng) {
  const SynthSyllable& syl = plan.syllables[i];
  Burst b;
  b.amp = (syl.stressed ? 0.30 : 0.14) * rng.uniform(0.85, 1.15);
  b.decay = syl.stressed ? rng.uniform(0.11, 0.15) : rng.uniform(0.08, 0.11);
  b.tau = b.decay / 3.0;  // the burst has fallen to 5% after `decay`
  b.f0 = f0_speaker * (syl.stressed ? 1.15 : 1.0) * (1.0 - 0.12 * progress) * rng.uniform(0.96, 1.04);
  b.glide = syl.stressed ? -0.10 : -0.04;  // relative pitch change over the syllable
  b.consonant_amp = b.amp * rng.uniform(0.3, 0.5);
  // The burst lasts until the next syllable starts (or 2.5 decays), with a 5 ms fade-out.
  b.length = 0.010 + 2.5 * b.decay;
  if (i + 1 < plan.syllables.size()) b.length = std::min(b.length, plan.syllables[i + 1].time - syl.time);
  b.harmonics = std::max(1, std::min(10, static_cast<int>(0.45 * sr / (b.f0 * 1.05))));
  b.norm = 0;
  for (int k = 1; k <= b.harmonics; ++k) b.norm += 1.0 / k;
  return b;
}

// Adds the burst starting at `time` to x: the harmonics under an attack/decay envelope, plus a
// short noise "consonant" at its start.
void render_burst(const Burst& b, double time, double sr, std::vector<double>& x, Rng& rng) {
  const std::size_t sample_count = x.size();
  const auto first = static_cast<std::size_t>(std::llround(time * sr));
  const auto n = static_cast<std::size_t>(std::llround(b.length * sr));
  double phase = 0;
  for (std::size_t s = 0; s < n && first + s < sample_count; ++s) {
    const double tt = static_cast<double>(s) / sr;
    double env = tt < Burst::kAttack ? 0.5 * (1.0 - std::cos(kPi * tt / Burst::kAttack))
                                     : std::exp(-(tt - Burst::kAttack) / b.tau);
    if (tt > b.length - Burst::kFade) env *= std::max(0.0, (b.length - tt) / Burst::kFade);
    // Harmonics sin(k*phase) by the Chebyshev recurrence (two trig calls per sample).
    const double s1 = std::sin(phase), c1 = std::cos(phase);
    double prev = 0, curv = s1, voiced = 0;
    for (int k = 1; k <= b.harmonics; ++k) {
      voiced += curv / k;
      const double next = 2.0 * c1 * curv - prev;
      prev = curv;
      curv = next;
    }
    double v = b.amp * env * voiced / b.norm;
    if (tt < Burst::kConsonantLen)
      v += b.consonant_amp * 0.5 * (1.0 - std::cos(2.0 * kPi * tt / Burst::kConsonantLen)) * rng.gaussian();
    x[first + s] += v;
    const double f = b.f0 * (1.0 + b.glide * tt / b.length);
    phase += 2.0 * kPi * f / sr;
    if (phase > 2.0 * kPi) phase -= 2.0 * kPi;
  }
}

}  // namespace

audio::Audio synth_audio(const SpeechPlan& plan, const SynthSpec& spec, std::size_t sample_count, Rng& rng) {
  const double sr = spec.sample_rate;
  std::vector<double> x(sample_count);
  for (double& v : x) v = 1e-3 * rng.gaussian();  // background noise

  const double f0_speaker = 110.0 + 90.0 * spec.style + rng.uniform(0.0, 15.0);  // 110..215 Hz
  std::size_t phrase = 0;
  for (std::size_t i = 0; i < plan.syllables.size(); ++i) {
    const SynthSyllable& syl = plan.syllables[i];
    while (phrase + 1 < plan.phrases.size() && plan.phrases[phrase].end < syl.time) ++phrase;
    const SynthPhrase& ph = plan.phrases[phrase];
    const double progress = ph.end > ph.start ? std::clamp((syl.time - ph.start) / (ph.end - ph.start), 0.0, 1.0) : 0.0;
    render_burst(draw_burst(plan, i, progress, f0_speaker, sr, rng), syl.time, sr, x, rng);
  }
  // Quantise to the PCM16 grid, so writing and reading a WAV gives back the same samples.
  audio::Audio a;
  a.sample_rate = spec.sample_rate;
  a.samples.resize(sample_count);
  for (std::size_t s = 0; s < sample_count; ++s) {
    const double q = std::clamp(std::round(x[s] * 32768.0), -32768.0, 32767.0);
    a.samples[s] = static_cast<float>(q / 32768.0);
  }
  return a;
}

}  // namespace gmg::synth_internal
