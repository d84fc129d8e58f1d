// Onset detection as librosa 0.10.2 does it (SPEC "Key nodes" -> "Onset nodes").
//
// onset_strength_envelope reproduces librosa.onset.onset_strength(y, sr=22050)
// frame by frame; detect_onsets reproduces librosa.onset.onset_detect's peak
// picking (librosa.util.peak_pick with onset_detect's defaults on the
// envelope normalised to [0, 1]), keeps the peaks whose raw strength reaches
// min_onset_strength, and backtracks them with librosa.onset.onset_backtrack.
#pragma once

#include <vector>

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

// librosa.onset.onset_strength(y=y, sr=22050) with its defaults. Resamples to
// 22050 Hz internally (resample_poly) when audio.sample_rate differs.
// Empty audio gives an envelope of one frame (0). Throws gmg::Error when
// audio.sample_rate is not positive.
std::vector<float> onset_strength_envelope(const Audio& audio);

// The same, taking the audio: its samples are released when the envelope is done, not kept by the
// caller beside the analysis (an hour at 16 kHz is 230 MB). The audio is resampled to 22050 Hz a
// stretch at a time as the spectrogram reaches it, so the analysis never holds it twice.
std::vector<float> onset_strength_envelope(Audio&& audio);

// Envelope, peak picking, the raw-strength filter and backtracking.
OnsetAnalysis detect_onsets(const Audio& audio, const OnsetParams& params);
OnsetAnalysis detect_onsets(Audio&& audio, const OnsetParams& params);

// The same on an envelope computed elsewhere (e.g. librosa's own, for tests):
// peak picking on the normalised envelope, the raw-strength filter and
// backtracking. The result's `envelope` is `envelope`.
OnsetAnalysis detect_onsets_in_envelope(const std::vector<float>& envelope, const OnsetParams& params);

// librosa.power_to_db(power, ref=1, amin=1e-10) without top_db, 10 log10(max(1e-10, power)), as
// the spectrogram computes it eight values at a time (exposed for tests): within a few units in the
// last place of 10 * std::log10; +inf stays +inf, NaN gives -100 as std::max(1e-10, NaN) does.
double power_to_db(double power);

// Motion frames of the onsets: round(t * fps) of every onset time, sorted,
// without duplicates. Onsets outside [0, num_frames) are dropped, not clipped:
// a reference's audio often outlasts its motion, and its trailing onsets
// belong to no frame. Empty when num_frames <= 0 or fps <= 0.
std::vector<int> onset_motion_frames(const OnsetAnalysis& a, double fps, int num_frames);

}  // namespace gmg::audio
