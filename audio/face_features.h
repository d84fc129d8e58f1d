// What the face track compares between the reference's speech and new speech when it has no phones
// to go by, frame by frame on the motion's grid: how loud, how voiced, and the shape of the
// spectrum. The jaw opens with loudness and with the first formant (energy between 300 and 1200
// Hz), closes on stops and nasals, and fricatives are noise high in the spectrum; so a frame's
// features are
//   loudness   (energy dB - the recording's speaking level) / 10 dB, clamped to [-4, 1], as in
//              audio/speech_features.h but not smoothed: faces change at the rate of phones;
//   voicing    zero crossings per millisecond (high for fricatives, low for vowels and nasals);
//   spectrum   the power of 6 bands (0-300, 300-700, 700-1200, 1200-2000, 2000-3500, 3500-8000
//              Hz) in dB relative to their sum, over 10 dB.
// Voicing and spectrum are taken relative to the recording's own mean over its speaking frames
// (a microphone's colour cancels), and fade to 0 in pauses (audio/speech_features.h pause_weight),
// where the spectrum is only noise.
#pragma once

#include <vector>

#include "audio/speech_energy.h"
#include "audio/wav.h"

namespace gmg::audio {

// The spectrum and voicing at a fixed rate, computed once from the samples (as EnergyTrack is), so
// the audio can be released before the motion's frame grid is known. Frame k is centred at k /
// kRateHz s: a Hann window of 32 ms (the audio averaged down to 16 to 32 kHz first), zero crossings
// over the same samples.
struct FaceAudio {
  static constexpr double kRateHz = 50.0;
  static constexpr int kBands = 6;
  std::vector<float> band_db;    // frames x kBands: 10 log10 of each band's power
  std::vector<float> crossings;  // one per frame: zero crossings per millisecond
  int frames() const { return static_cast<int>(crossings.size()); }
};

// Throws gmg::Error when audio.sample_rate is not positive. Empty audio gives no frames.
FaceAudio face_audio(const Audio& audio);

struct FaceFeatures {
  static constexpr int kDims = 2 + FaceAudio::kBands;  // loudness, voicing, 6 bands
  std::vector<float> values;                           // frames x kDims, frame-major
  int frames() const { return static_cast<int>(values.size() / kDims); }
};

// Features of `frames` frames at `fps` (frame f at f / fps s, the fixed-rate track read between its
// frames linearly). Frames past the audio's end are silent. fps > 0, frames >= 0.
FaceFeatures face_features(const FaceAudio& track, const EnergyTrack& energy, double fps, int frames);

}  // namespace gmg::audio
