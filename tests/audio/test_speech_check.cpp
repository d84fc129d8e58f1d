// Tests of audio/speech_check: which recordings can be speech. The thresholds are the documented
// ones (0.5 s, -60 dB full scale for the loudest second, an onset in 10 s), checked on signals
// whose level is known in closed form, and on the project's own synthetic speaker, which every
// demo and many tests reenact and so must pass.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "audio/onset.h"
#include "audio/speech_check.h"
#include "audio/speech_energy.h"
#include "engine/synth/synth.h"
#include "tests/test_support.h"

namespace gmg::audio {
namespace {

// `seconds` of a sine of amplitude `peak` (RMS peak / sqrt 2) at 16 kHz, starting at `from_s`
// (silence before), so its level in dB full scale is 20 log10(peak / sqrt 2).
Audio sine(double seconds, double peak, double from_s = 0.0) {
  Audio a;
  a.sample_rate = 16000;
  a.samples.assign(static_cast<std::size_t>(std::lround((from_s + seconds) * a.sample_rate)), 0.0f);
  for (std::size_t i = static_cast<std::size_t>(std::lround(from_s * a.sample_rate)); i < a.samples.size(); ++i)
    a.samples[i] = static_cast<float>(peak * std::sin(2.0 * M_PI * 220.0 * static_cast<double>(i) / a.sample_rate));
  return a;
}

TEST(SpeechCheck, LoudestSecondIsTheSinesLevel) {
  const double peak = 0.1;  // -23.0 dB full scale
  EXPECT_NEAR(loudest_second_db(energy_track(sine(3.0, peak))), 20.0 * std::log10(peak / std::sqrt(2.0)), 0.05);
  // One loud second in ten of silence: the loudest window finds it.
  EXPECT_NEAR(loudest_second_db(energy_track(sine(1.0, peak, 5.0))), 20.0 * std::log10(peak / std::sqrt(2.0)), 0.05);
  // Shorter than a second: the whole track.
  EXPECT_NEAR(loudest_second_db(energy_track(sine(0.5, peak))), 20.0 * std::log10(peak / std::sqrt(2.0)), 0.05);
  EXPECT_EQ(loudest_second_db(energy_track(sine(2.0, 0.0))), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(loudest_second_db(EnergyTrack{}), -std::numeric_limits<double>::infinity());
}

TEST(SpeechCheck, SilenceAndClicksOfAudioAreNotSpeech) {
  const auto level = [](const Audio& a) { return speech_level_problem(a.duration(), energy_track(a)); };
  EXPECT_EQ(level(sine(0.01, 0.5)),
            "holds 0.01 s of audio, too short to be speech (gmg needs at least 0.5 s; --allow-silence uses it anyway)");
  EXPECT_EQ(level(sine(60.0, 0.0)),
            "is silent: every sample is zero, and speech needs -60 dB or more; --allow-silence uses it anyway");
  // A hiss at -70 dB (peak 4.5e-4) is silent; the same at -50 dB is loud enough.
  EXPECT_EQ(level(sine(5.0, std::sqrt(2.0) * 3.16e-4)),
            "is silent: its loudest second is at -70.0 dB full scale, and speech needs -60 dB or more; --allow-silence "
            "uses it anyway");
  EXPECT_EQ(level(sine(5.0, std::sqrt(2.0) * 3.16e-3)), "");
  EXPECT_EQ(level(sine(0.5, 0.3)), "");  // exactly the shortest
}

TEST(SpeechCheck, LongAudioWithoutAnyOnsetIsNotSpeech) {
  EXPECT_EQ(speech_onset_problem(60.0, 0, 5.0),
            "has no onset in 60.0 s of audio: a steady sound or noise, not speech (no syllable starts with onset "
            "strength 5 or more, the min_onset_strength key; --allow-silence uses it anyway)");
  EXPECT_EQ(speech_onset_problem(60.0, 1, 5.0), "");
  EXPECT_EQ(speech_onset_problem(kOnsetlessSeconds, 0, 5.0), "");  // a short pause-only clip may be quiet
  // A steady tone of 12 s: loud, but no syllable starts.
  const Audio tone = sine(12.0, 0.3);
  EXPECT_EQ(speech_level_problem(tone.duration(), energy_track(tone)), "");
  const OnsetAnalysis onsets = detect_onsets(tone, OnsetParams{});
  EXPECT_NE(speech_onset_problem(tone.duration(), onsets.onset_frames.size(), 5.0), "");
}

TEST(SpeechCheck, TheSyntheticSpeakersPass) {
  for (const double duration : {1.0, 2.0, 12.0, 60.0})
    for (const int rate : {8000, 16000}) {
      SynthSpec spec;
      spec.duration_s = duration;
      spec.sample_rate = rate;
      spec.seed = static_cast<std::uint64_t>(duration * 10) + static_cast<std::uint64_t>(rate);
      const SynthClip clip = synth_speaker(spec);
      const Audio& a = clip.audio;
      EXPECT_EQ(speech_level_problem(a.duration(), energy_track(a)), "") << duration << " s at " << rate << " Hz";
      const OnsetAnalysis onsets = detect_onsets(a, OnsetParams{});
      EXPECT_EQ(speech_onset_problem(a.duration(), onsets.onset_frames.size(), 5.0), "") << duration << " s";
    }
}

}  // namespace
}  // namespace gmg::audio
