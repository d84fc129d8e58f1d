// Speech-motion synchrony with a control: every sync metric is computed against the test audio
// as it is ("aligned") and against the same audio circularly shifted by several deterministic
// offsets (no synchrony possible). lift = aligned - mean(shifted). A lift within the spread of the
// shifted values means the metric saw no synchrony: it rises with how much the motion moves, not
// with when.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "audio/wav.h"
#include "engine/metrics/metrics.h"

namespace gmg {

// What a metric needs of one version of the audio: the onset times (the BC audio beats, the
// librosa-style detector at its default threshold) and the onset strength envelope.
struct SpeechTrack {
  std::vector<double> onset_times_s;
  std::vector<float> envelope;  // one value per 512 samples at 22050 Hz
};

struct SyncControl {
  SpeechTrack aligned;
  std::vector<double> shifts_s;      // the circular shifts, seconds
  std::vector<SpeechTrack> shifted;  // one per shift
};

// `count` circular shifts spread evenly over [min_shift_s, duration_s - min_shift_s], so each is
// at least min_shift_s away from alignment in both directions. gmg::Error when the audio is too
// short for that (duration < 2 * min_shift_s + 1 s) or count < 2.
std::vector<double> control_shifts(double duration_s, int count, double min_shift_s);

// The audio rotated by shift_s: output sample i is input sample (i + round(shift_s * rate)) mod n,
// so what was heard at time t + shift is heard at t.
audio::Audio circular_shift(const audio::Audio& sound, double shift_s);

SpeechTrack speech_track(const audio::Audio& sound);

// The aligned track and `count` shifted ones (default: 8 shifts of at least 2 s).
SyncControl sync_control(const audio::Audio& sound, int count = 8, double min_shift_s = 2.0);

struct ControlledScore {
  double aligned = 0.0;
  std::vector<double> shifted;  // one per shift
  double shifted_mean() const;
  double shifted_sd() const;  // sample standard deviation of the shifted values
  double lift() const { return aligned - shifted_mean(); }
};

// Speech-motion correlation (unitless, [-1, 1]): log(1 + onset strength) averaged over each motion
// frame's time window, against the mean root-relative joint speed of that frame, both smoothed
// over 0.2 s; the largest Pearson correlation over lags of the motion of -max_lag_s..+max_lag_s.
// Gestures move most around stressed syllables, so real motion correlates with its own speech's
// onset strength and not with another stretch of it. Measured on the shared recordings' truth
// (thirds of 21-23 s, 8 shifts): ZEGGS 0.36-0.68 aligned against 0.03-0.07 shifted (2.7-4.4
// shifted sd above); BEAT2 scott 0.10-0.15 against 0.04-0.07 (0.5-1.2 sd: its capture shows
// little speech-motion synchrony at all, BC's lift is no larger). Needs >= 3 frames; 0 when
// either signal is constant.
double metric_speech_correlation(const Eigen::MatrixXd& pos, double fps, const std::vector<float>& envelope,
                                 double max_lag_s = 0.25);

// BC and the speech correlation against the aligned and every shifted track.
ControlledScore bc_controlled(const Eigen::MatrixXd& pos, double fps, const SyncControl& control,
                              const MetricParams& params);
ControlledScore speech_correlation_controlled(const Eigen::MatrixXd& pos, double fps, const SyncControl& control);

}  // namespace gmg
