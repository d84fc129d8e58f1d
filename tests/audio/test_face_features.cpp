// audio/face_features.h: the spectrum, voicing and loudness the face track compares speech by.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "audio/face_features.h"
#include "audio/speech_energy.h"
#include "engine/core/error.h"

namespace gmg::audio {
namespace {

constexpr double kPi = 3.14159265358979323846;

Audio tone(double hz, double seconds, int rate = 16000, double amplitude = 0.5) {
  Audio a;
  a.sample_rate = rate;
  a.samples.resize(static_cast<std::size_t>(std::lround(seconds * rate)));
  for (std::size_t i = 0; i < a.samples.size(); ++i)
    a.samples[i] = static_cast<float>(amplitude * std::sin(2.0 * kPi * hz * static_cast<double>(i) / rate));
  return a;
}

// The band (0-300, 300-700, 700-1200, 1200-2000, 2000-3500, 3500-8000 Hz) holding most power at
// frame k of the track.
int loudest_band(const FaceAudio& t, int k) {
  const auto first = t.band_db.begin() + static_cast<std::ptrdiff_t>(k) * FaceAudio::kBands;
  return static_cast<int>(std::max_element(first, first + FaceAudio::kBands) - first);
}

TEST(FaceFeatures, ATonesPowerIsInItsBandAndItCrossesZeroTwicePerPeriod) {
  // One frame every 20 ms, centred at k / 50 s: 2 s give 100 frames.
  const FaceAudio t1k = face_audio(tone(1000.0, 2.0));
  ASSERT_EQ(t1k.frames(), 100);
  ASSERT_EQ(t1k.band_db.size(), 100u * FaceAudio::kBands);
  EXPECT_EQ(loudest_band(t1k, 50), 2);  // 700-1200 Hz
  // 1 kHz crosses zero 2000 times a second: 2 per millisecond (to one crossing in the 32 ms window).
  EXPECT_NEAR(t1k.crossings[50], 2.0, 1.0 / 32.0 + 1e-9);
  // A tone at 5 kHz: the top band, 10 crossings per millisecond; at 44.1 kHz the same.
  const FaceAudio t5k = face_audio(tone(5000.0, 2.0));
  EXPECT_EQ(loudest_band(t5k, 50), 5);
  EXPECT_NEAR(t5k.crossings[50], 10.0, 1.0 / 32.0 + 1e-9);
  const FaceAudio t5k44 = face_audio(tone(5000.0, 2.0, 44100));
  EXPECT_EQ(t5k44.frames(), 100);
  EXPECT_EQ(loudest_band(t5k44, 50), 5);
  // Silence: every band at the floor (10 log10 of 1e-12), no crossing; no samples, no frames.
  const FaceAudio quiet = face_audio(tone(1000.0, 1.0, 16000, 0.0));
  for (float db : quiet.band_db) EXPECT_FLOAT_EQ(db, -120.0f);
  EXPECT_EQ(quiet.crossings[10], 0.0f);
  Audio empty;
  empty.sample_rate = 16000;
  EXPECT_EQ(face_audio(empty).frames(), 0);
  empty.sample_rate = 0;
  EXPECT_THROW(face_audio(empty), Error);
}

TEST(FaceFeatures, OnTheMotionsGridRelativeToTheSpeakingMeanAndQuietInPauses) {
  // 1 s of a 500 Hz tone, 1 s of silence, 1 s of a 3 kHz tone.
  Audio a = tone(500.0, 1.0);
  a.samples.resize(32000, 0.0f);
  const Audio high = tone(3000.0, 1.0);
  a.samples.insert(a.samples.end(), high.samples.begin(), high.samples.end());
  const FaceFeatures f = face_features(face_audio(a), energy_track(a), 30.0, 90);
  ASSERT_EQ(f.frames(), 90);
  constexpr int D = FaceFeatures::kDims;
  const auto at = [&](int frame, int dim) { return f.values[static_cast<std::size_t>(frame * D + dim)]; };
  // Loudness within [-4, 1]: about the speaking level in both tones, at the floor in the silence.
  EXPECT_NEAR(at(15, 0), 0.0, 0.5);
  EXPECT_NEAR(at(75, 0), 0.0, 0.5);
  EXPECT_FLOAT_EQ(at(45, 0), -4.0f);
  // Relative to the mean over speaking frames: the low tone is voiced less than the mean and
  // richer in its own band (300-700 Hz), the high tone the other way round; the pause is 0.
  EXPECT_LT(at(15, 1), 0.0f);
  EXPECT_GT(at(75, 1), 0.0f);
  EXPECT_GT(at(15, 2 + 1), 0.0f);
  EXPECT_LT(at(75, 2 + 1), 0.0f);
  EXPECT_GT(at(75, 2 + 4), 0.0f);
  for (int d = 1; d < D; ++d) EXPECT_EQ(at(45, d), 0.0f) << d;
  // Past the audio's end: silent.
  const FaceFeatures longer = face_features(face_audio(a), energy_track(a), 30.0, 120);
  EXPECT_FLOAT_EQ(longer.values[static_cast<std::size_t>(110 * D)], -4.0f);
  EXPECT_THROW(face_features(face_audio(a), energy_track(a), 0.0, 10), Error);
}

}  // namespace
}  // namespace gmg::audio
