// Onset detection as librosa 0.10.2 does it (SPEC "Key nodes" -> "Onset nodes").
//
// onset_strength_envelope (audio/onset_strength.h, the spectral front end) reproduces
// librosa.onset.onset_strength(y, sr=22050) frame by frame; detect_onsets reproduces librosa.onset.onset_detect's peak
// picking (librosa.util.peak_pick with onset_detect's defaults on the
// envelope normalised to [0, 1]), keeps the peaks whose raw strength reaches
// min_onset_strength, and backtracks them with librosa.onset.onset_backtrack.
#pragma once

#include <vector>

#include "audio/onset_strength.h"
#include "audio/wav.h"

namespace gmg::audio {

struct OnsetParams {
  // Raw envelope value a peak must reach to be kept (the unit is the mean
  // per-band rise in dB from one frame to the next). Default: SPEC.
  double min_onset_strength = 5.0;
  // librosa.util.peak_pick parameters in envelope frames (onset_detect's
  // defaults at sr 22050, hop 512). All >= 0 except post_max and post_avg >= 1.
  int pre_max = 1, post_max = 1, pre_avg = 4, post_avg = 5, wait = 1;
  // Threshold above the local mean, on the envelope normalised to [0, 1].
  double delta = 0.07;
};

struct OnsetAnalysis {
  static constexpr int kSampleRate = 22050, kHop = 512, kNfft = 2048, kMels = 128;
  // Onset strength per envelope frame; frame k is at time k * 512 / 22050 s.
  // As in librosa: one value per STFT frame (1 + samples_at_22050 / 512),
  // >= 0, and the first 3 frames are 0 (lag 1 plus librosa's centring shift).
  std::vector<float> envelope;
  // Kept peaks (envelope frames), strictly increasing.
  std::vector<int> peak_frames;
  // Raw envelope values at the kept peaks (each >= min_onset_strength).
  std::vector<float> peak_strengths;
  // One per kept peak: the peak backtracked to the last local minimum of
  // the envelope at or before it (0 when there is none). Non-decreasing;
  // two peaks may backtrack to the same frame.
  std::vector<int> onset_frames;

  // onset_frames converted to seconds (frame * 512 / 22050).
  std::vector<double> onset_times() const;
};

// Envelope, peak picking, the raw-strength filter and backtracking.
OnsetAnalysis detect_onsets(const Audio& audio, const OnsetParams& params);
OnsetAnalysis detect_onsets(Audio&& audio, const OnsetParams& params);

// The same on an envelope computed elsewhere (e.g. librosa's own, for tests):
// peak picking on the normalised envelope, the raw-strength filter and
// backtracking. The result's `envelope` is `envelope`.
OnsetAnalysis detect_onsets_in_envelope(const std::vector<float>& envelope, const OnsetParams& params);

// Motion frames of the onsets: round(t * fps) of every onset time, sorted,
// without duplicates. Onsets outside [0, num_frames) are dropped, not clipped:
// a reference's audio often outlasts its motion, and its trailing onsets
// belong to no frame. Empty when num_frames <= 0 or fps <= 0.
std::vector<int> onset_motion_frames(const OnsetAnalysis& a, double fps, int num_frames);

}  // namespace gmg::audio
