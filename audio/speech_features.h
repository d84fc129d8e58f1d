// What the planner compares between the reference's speech and new speech, frame by frame on the
// motion's grid (SPEC "Speech-driven search"): how loud, and how much onset activity (syllables).
//
// Each recording is normalised by its own level, so a quiet and a loud recording of the same
// speaking style look alike, and a pause looks like a pause whatever the microphone gain:
//   loudness  = (energy dB - the recording's speaking level) / 10 dB, clamped to [-4, 1]; the
//               speaking level is the 90th percentile of the frames' energy (audio/speech_energy.h),
//               so -4 is 40 dB below speech: silence.
//   onsets    = log(1 + onset strength) per frame (the mean envelope value of audio/onset_strength.h over the
//               frame), over its 90th percentile, clamped to [0, 3].
// Both smoothed by a centred moving average over smooth_s (9 frames at 30 fps): syllables come
// 4-6 a second, and a gesture follows the phrase's loudness, not each syllable.
#pragma once

#include <vector>

#include "audio/speech_energy.h"

namespace gmg::audio {

struct SpeechFeatures {
  static constexpr int kDims = 2;  // loudness, onsets
  std::vector<float> values;       // frames x kDims, frame-major
  int frames() const { return static_cast<int>(values.size() / kDims); }
};

// Features of `frames` frames at `fps` from a recording's energy track and onset envelope
// (OnsetAnalysis::envelope: one value per 512 samples at 22050 Hz). Frames past the audio's end
// are silent. fps > 0, frames >= 0.
SpeechFeatures speech_features(const EnergyTrack& energy, const std::vector<float>& envelope, double fps, int frames,
                               double smooth_s = 0.3);

// The p-th percentile (0..100) by nearest rank of a copy of v (the speaking level is the 90th of
// the frames' energy); 0 for an empty v.
double percentile_of(std::vector<double> v, double p);

// How much a frame of loudness `loudness` (as above) is a pause: 0 down to 20 dB below the speaking
// level, rising to 1 at 35 dB below.
inline float pause_weight(float loudness) {
  const float w = (-loudness - 2.0f) / 1.5f;
  return w < 0.0f ? 0.0f : (w > 1.0f ? 1.0f : w);
}

}  // namespace gmg::audio
