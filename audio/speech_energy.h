// Loudness of speech over time: the RMS energy the planner matches between reference and test
// speech, and the sync metrics correlate with motion.
#pragma once

#include <vector>

#include "audio/wav.h"

namespace gmg::audio {

// The mean square of the samples in consecutive bins of 1 / kRateHz seconds (the last bin may be
// shorter; it is the mean of what it holds). Computed once from the samples, so the audio can be
// released before the frame grid it will be put on is known.
struct EnergyTrack {
  static constexpr double kRateHz = 200.0;  // 5 ms: finer than any motion frame rate used
  std::vector<float> mean_square;
};

// Throws gmg::Error when audio.sample_rate is not positive. Empty audio gives an empty track.
EnergyTrack energy_track(const Audio& audio);

// Energy in dB (10 log10 of the mean square) per frame of a grid of `fps`: frame f pools the bins
// whose centre rounds to f (round(t * fps)), so each frame covers its own 1 / fps. Never below
// kSilenceDb (digital silence, and frames past the audio's end, take it).
inline constexpr float kSilenceDb = -100.0f;
std::vector<float> energy_db_on_grid(const EnergyTrack& track, double fps, int frames);

}  // namespace gmg::audio
