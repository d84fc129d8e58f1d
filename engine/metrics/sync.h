// Speech-motion synchrony with a control: every sync metric is computed against the test audio
// as it is ("aligned") and against the same audio circularly shifted by several deterministic
// offsets (no synchrony possible). lift = aligned - mean(shifted). A lift within the spread of the
// shifted values means the metric saw no synchrony: it rises with how much the motion moves, not
// with when.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "audio/speech_energy.h"
#include "audio/wav.h"
#include "engine/metrics/metrics.h"

namespace gmg {

// What a metric needs of one version of the audio: the onset times (the BC audio beats, the
// detector at the graph's default threshold), librosa's own onsets (onset_detect's peaks with no
// strength threshold, backtracked: the beats EMAGE-style beat consistency uses), the onset
// strength envelope and the energy.
struct SpeechTrack {
  std::vector<double> onset_times_s;
  std::vector<double> beat_times_s;
  std::vector<float> envelope;  // one value per 512 samples at 22050 Hz
  audio::EnergyTrack energy;
  double duration_s = 0.0;
};

// Two controls: the same audio circularly shifted (no synchrony possible with the motion), and
// other speech (GENEA's appropriateness test pairs a motion with mismatched speech: other folds of
// the recording, or other clips). A metric against another speech is computed over the frames both
// span.
struct SyncControl {
  SpeechTrack aligned;
  std::vector<double> shifts_s;         // the circular shifts, seconds
  std::vector<SpeechTrack> shifted;     // one per shift
  std::vector<SpeechTrack> mismatched;  // other speech; may be empty
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
  std::vector<double> shifted;     // one per shift
  std::vector<double> mismatched;  // one per other speech
  double shifted_mean() const;
  double shifted_sd() const;  // sample standard deviation of the shifted values
  double lift() const { return aligned - shifted_mean(); }
  double mismatched_mean() const;
  double mismatched_sd() const;
  // aligned - mean(mismatched): what the motion shares with its own speech and not with other
  // speech. 0 without other speech.
  double mismatched_lift() const { return mismatched.empty() ? 0.0 : aligned - mismatched_mean(); }
};

// Speech-motion correlation (unitless, [-1, 1]): log(1 + onset strength) averaged over each motion
// frame's time window, against the mean root-relative joint speed of that frame, both smoothed
// over 0.2 s; the largest Pearson correlation over lags of the motion of -max_lag_s..+max_lag_s.
// Gestures move most around stressed syllables, so real motion correlates with its own speech's
// onset strength and not with another stretch of it (the shared recordings' captures score:
// docs/evaluation.md). Needs >= 3 frames; 0 when either signal is constant.
double metric_speech_correlation(const Eigen::MatrixXd& pos, double fps, const std::vector<float>& envelope,
                                 double max_lag_s = 0.25);

// Energy correlation (unitless, [-1, 1]): the Pearson correlation of the upper body's motion
// energy with the speech's loudness, frame by frame, no lag. Motion: the mean root-relative speed
// |p(t) - p(t-1)| * fps of `joints` (engine/motion/body_parts.h upper_body_joints; frame 0 takes
// frame 1's). Speech: energy in dB per motion frame (audio/speech_energy.h), floored 60 dB below
// its loudest frame so digital silence does not decide the result. Both smoothed by a centred
// moving average of 2 * round(smooth_s * fps / 2) + 1 frames (15 at 30 fps) and compared over the
// frames both have. A speaker moves more while speaking loudly and rests in pauses; a stretch of
// motion does not share that with another speech. 0 when either signal is constant. Needs >= 3
// frames.
double metric_energy_correlation(const Eigen::MatrixXd& pos, double fps, const std::vector<int>& joints,
                                 const audio::EnergyTrack& energy, double smooth_s = 0.5);

// Kinematic beat consistency, EMAGE's rule (BEAT2's benchmark). Per joint j of `joints`: its
// root-relative speed (central difference; one-sided at the ends) over mean_speed[j] (the
// reference capture's mean speed of that joint, joint_mean_speeds); its motion beats are the
// frames lower than each of the `order` frames on either side (frames past the ends do not count
// as lower) where that ratio is above `threshold` (a minimum inside a rest is no beat); its score
// the mean over audio beats of exp(-d^2 / (2 sigma^2)), d the distance to its nearest beat (0
// without beats). BC = mean over joints. No audio beats: 0.
struct KinematicBeatParams {
  double sigma_s = 0.3;
  int order = 7;
  double threshold = 0.3;
};
double metric_bc_kinematic(const Eigen::MatrixXd& pos, double fps, const std::vector<int>& joints,
                           const std::vector<double>& mean_speed, const std::vector<double>& audio_beats_s,
                           const KinematicBeatParams& params = {});

// Each joint's mean root-relative speed (central differences as metric_bc_kinematic takes them).
std::vector<double> joint_mean_speeds(const Eigen::MatrixXd& pos, double fps);

// BC and the speech correlation against the aligned, every shifted and every mismatched track.
ControlledScore bc_controlled(const Eigen::MatrixXd& pos, double fps, const SyncControl& control,
                              const MetricParams& params);
ControlledScore speech_correlation_controlled(const Eigen::MatrixXd& pos, double fps, const SyncControl& control);
ControlledScore energy_correlation_controlled(const Eigen::MatrixXd& pos, double fps, const std::vector<int>& joints,
                                              const SyncControl& control);
ControlledScore bc_kinematic_controlled(const Eigen::MatrixXd& pos, double fps, const std::vector<int>& joints,
                                        const std::vector<double>& mean_speed, const SyncControl& control);

}  // namespace gmg
