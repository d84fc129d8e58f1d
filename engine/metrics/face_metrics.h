// How well a face speaks its speech: the jaw's opening against the speech's loudness, open vowels
// against lips closed, and expressions beyond the reference's. Definitions as `gmg evaluate` reports
// them (docs/method.md "The face"):
//   jaw                  the angle of the jaw joint's local rotation (SMPL-X joint 22), radians;
//   jaw-energy correlation  Pearson correlation of the jaw with the speech's RMS energy over each
//                        motion frame, both smoothed over 3 frames, lag 0;
//   viseme contrast      mean jaw over the frames of open vowels (AA AE AH AO AW AY) / mean jaw over
//                        those of bilabials (P B M);
//   out of range         share of frames with any expression coefficient outside the reference's
//                        per-coefficient [min - margin, max + margin].
#pragma once

#include <optional>
#include <vector>

#include "audio/wav.h"
#include "engine/motion/motion.h"

namespace gmg {

// The jaw's angle at every frame of m; empty when its skeleton has no jaw (engine/motion/body_parts.h).
std::vector<double> jaw_angles(const Motion& m);

// The speech's RMS energy over each of `frames` frames of `fps` (frame f: samples from (f - 0.5) /
// fps to (f + 0.5) / fps s; 0 past the audio's end).
std::vector<double> frame_rms(const audio::Audio& sound, double fps, int frames);

// Pearson correlation of jaw and energy (the shorter length), both smoothed over 3 frames; nullopt
// when either is constant or shorter than 3 frames.
std::optional<double> jaw_energy_correlation(const std::vector<double>& jaw, const std::vector<double>& energy);

// A stretch of speech the viseme contrast reads: frames [start, end) at the motion's rate.
struct MouthSpan {
  double start = 0.0, end = 0.0;  // seconds
  bool open = false;              // an open vowel; false: a bilabial
};

// Mean jaw in open vowels over mean jaw in bilabials; nullopt without frames of either or when the
// bilabials' mean is 0.
std::optional<double> viseme_contrast(const std::vector<double>& jaw, const std::vector<MouthSpan>& spans, double fps);

// Share (0 to 1) of the frames of `expressions` (frames x dims) with any coefficient outside the
// reference's range widened by margin. Both must have `dims` coefficients.
double expressions_out_of_range(const std::vector<double>& expressions, const std::vector<double>& reference, int dims,
                                double margin);

}  // namespace gmg
