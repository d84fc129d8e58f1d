#include "engine/metrics/sync.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "audio/onset.h"
#include "audio/speech_energy.h"
#include "engine/core/error.h"
#include "engine/core/math.h"
#include "engine/metrics/naturalness.h"

namespace gmg {

std::vector<double> control_shifts(double duration_s, int count, double min_shift_s) {
  if (count < 2) throw Error("sync control: needs at least 2 shifts, got " + std::to_string(count));
  if (!(duration_s >= 2.0 * min_shift_s + 1.0))
    throw Error("sync control: the audio lasts " + std::to_string(duration_s) + " s; shifts of at least " +
                std::to_string(min_shift_s) + " s need " + std::to_string(2.0 * min_shift_s + 1.0) + " s");
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(count));
  const double span = duration_s - 2.0 * min_shift_s;
  for (int k = 0; k < count; ++k) out.push_back(min_shift_s + span * k / (count - 1));
  return out;
}

audio::Audio circular_shift(const audio::Audio& sound, double shift_s) {
  audio::Audio out;
  out.sample_rate = sound.sample_rate;
  const std::size_t n = sound.samples.size();
  if (n == 0) return out;
  const long long k = std::llround(shift_s * sound.sample_rate);
  const std::size_t offset = static_cast<std::size_t>(((k % static_cast<long long>(n)) + static_cast<long long>(n)) %
                                                      static_cast<long long>(n));
  out.samples.resize(n);
  std::rotate_copy(sound.samples.begin(), sound.samples.begin() + static_cast<std::ptrdiff_t>(offset),
                   sound.samples.end(), out.samples.begin());
  return out;
}

SpeechTrack speech_track(const audio::Audio& sound) {
  const audio::OnsetAnalysis a = audio::detect_onsets(sound, audio::OnsetParams{});
  audio::OnsetParams librosa;
  librosa.min_onset_strength = 0.0;
  SpeechTrack t;
  t.onset_times_s = a.onset_times();
  t.beat_times_s = audio::detect_onsets_in_envelope(a.envelope, librosa).onset_times();
  t.envelope = a.envelope;
  t.energy = audio::energy_track(sound);
  t.duration_s = sound.duration();
  return t;
}

SyncControl sync_control(const audio::Audio& sound, int count, double min_shift_s) {
  SyncControl c;
  c.shifts_s = control_shifts(sound.duration(), count, min_shift_s);
  c.aligned = speech_track(sound);
  for (double s : c.shifts_s) c.shifted.push_back(speech_track(circular_shift(sound, s)));
  return c;
}

namespace {

double mean_of(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double sd_of(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean_of(v);
  double ss = 0.0;
  for (double x : v) ss += (x - m) * (x - m);
  return std::sqrt(ss / static_cast<double>(v.size() - 1));
}

}  // namespace

double ControlledScore::shifted_mean() const { return mean_of(shifted); }
double ControlledScore::shifted_sd() const { return sd_of(shifted); }
double ControlledScore::mismatched_mean() const { return mean_of(mismatched); }
double ControlledScore::mismatched_sd() const { return sd_of(mismatched); }

namespace {

// Pearson correlation of a[i] and b[i + lag] over the indices where both exist.
double correlation_at_lag(const std::vector<double>& a, const std::vector<double>& b, int lag) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  int n = 0;
  for (int i = 0; i < static_cast<int>(a.size()); ++i) {
    const int j = i + lag;
    if (j < 0 || j >= static_cast<int>(b.size())) continue;
    const double x = a[static_cast<std::size_t>(i)], y = b[static_cast<std::size_t>(j)];
    sa += x;
    sb += y;
    saa += x * x;
    sbb += y * y;
    sab += x * y;
    ++n;
  }
  if (n < 3) return 0.0;
  const double cov = sab - sa * sb / n, va = saa - sa * sa / n, vb = sbb - sb * sb / n;
  if (va <= 1e-12 * std::max(1.0, saa) || vb <= 1e-12 * std::max(1.0, sbb)) return 0.0;
  return cov / std::sqrt(va * vb);
}

}  // namespace

double metric_speech_correlation(const Eigen::MatrixXd& pos, double fps, const std::vector<float>& envelope,
                                 double max_lag_s) {
  if (pos.rows() < 3) throw Error("speech correlation: the motion needs at least 3 frames");
  const int frames = static_cast<int>(pos.rows());
  // Onset strength per motion frame: the mean of the envelope frames inside the frame's window.
  const double env_rate = static_cast<double>(audio::OnsetAnalysis::kSampleRate) / audio::OnsetAnalysis::kHop;
  std::vector<double> strength(static_cast<std::size_t>(frames), 0.0);
  std::vector<int> count(static_cast<std::size_t>(frames), 0);
  for (std::size_t k = 0; k < envelope.size(); ++k) {
    const int t = static_cast<int>(std::lround(static_cast<double>(k) / env_rate * fps));
    if (t < 0 || t >= frames) continue;
    // log1p: a few loud syllables should not decide the correlation alone.
    strength[static_cast<std::size_t>(t)] += std::log1p(std::max(0.0f, envelope[k]));
    ++count[static_cast<std::size_t>(t)];
  }
  for (int t = 0; t < frames; ++t)
    if (count[static_cast<std::size_t>(t)] > 0)
      strength[static_cast<std::size_t>(t)] /= count[static_cast<std::size_t>(t)];
  // Mean root-relative joint speed, frame t from t - 1 (frame 0 takes frame 1's).
  const Eigen::MatrixXd rel = root_relative(pos);
  const Eigen::Index joints = pos.cols() / 3;
  std::vector<double> speed(static_cast<std::size_t>(frames), 0.0);
  for (int t = 1; t < frames; ++t) {
    double sum = 0.0;
    for (Eigen::Index j = 1; j < joints; ++j) sum += (rel.block<1, 3>(t, 3 * j) - rel.block<1, 3>(t - 1, 3 * j)).norm();
    speed[static_cast<std::size_t>(t)] = sum / std::max<Eigen::Index>(1, joints - 1);
  }
  speed[0] = speed[1];
  // Both smoothed over ~0.2 s: gesture strokes and syllables align within a few frames, not
  // frame for frame.
  const int half = static_cast<int>(std::lround(0.1 * fps));
  strength = moving_average(strength, half);
  speed = moving_average(speed, half);
  const int max_lag = static_cast<int>(std::lround(max_lag_s * fps));
  double best = -1.0;
  for (int lag = -max_lag; lag <= max_lag; ++lag) best = std::max(best, correlation_at_lag(strength, speed, lag));
  return best;
}

namespace {

// Pearson correlation of a and b over their first min(size) samples; 0 when either is constant.
double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  if (n < 3) return 0.0;
  return correlation_at_lag(std::vector<double>(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(n)),
                            std::vector<double>(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(n)), 0);
}

// Root-relative speed of joint j at every frame: central differences, one-sided at the ends.
std::vector<double> central_speed(const Eigen::MatrixXd& rel, double fps, Eigen::Index j) {
  const Eigen::Index n = rel.rows();
  std::vector<double> v(static_cast<std::size_t>(n), 0.0);
  if (n < 2) return v;
  for (Eigen::Index t = 0; t < n; ++t) {
    const Eigen::Index a = std::max<Eigen::Index>(0, t - 1), b = std::min(n - 1, t + 1);
    v[static_cast<std::size_t>(t)] =
        (rel.block<1, 3>(b, 3 * j) - rel.block<1, 3>(a, 3 * j)).norm() * fps / static_cast<double>(b - a);
  }
  return v;
}

// The motion's audio-beat track for a speech: its beats inside the motion's span.
std::vector<double> beats_within(const std::vector<double>& beats, double duration_s) {
  std::vector<double> out;
  for (double b : beats)
    if (b < duration_s) out.push_back(b);
  return out;
}

}  // namespace

double metric_energy_correlation(const Eigen::MatrixXd& pos, double fps, const std::vector<int>& joints,
                                 const audio::EnergyTrack& energy, double smooth_s) {
  if (pos.rows() < 3) throw Error("energy correlation: the motion needs at least 3 frames");
  if (joints.empty()) throw Error("energy correlation: no upper-body joints");
  const int frames = static_cast<int>(pos.rows());
  const Eigen::MatrixXd rel = root_relative(pos);
  std::vector<double> speed(static_cast<std::size_t>(frames), 0.0);
  for (int t = 1; t < frames; ++t) {
    double sum = 0.0;
    for (int j : joints) sum += (rel.block<1, 3>(t, 3 * j) - rel.block<1, 3>(t - 1, 3 * j)).norm();
    speed[static_cast<std::size_t>(t)] = sum * fps / static_cast<double>(joints.size());
  }
  speed[0] = speed[1];
  // Frames the speech covers: past its end there is nothing to compare.
  const int covered =
      std::min(frames, static_cast<int>(std::floor(
                           static_cast<double>(energy.mean_square.size()) / audio::EnergyTrack::kRateHz * fps + 0.5)));
  if (covered < 3) return 0.0;
  const std::vector<float> db = audio::energy_db_on_grid(energy, fps, covered);
  const float loudest = *std::max_element(db.begin(), db.end());
  std::vector<double> loud(db.size());
  for (std::size_t i = 0; i < db.size(); ++i) loud[i] = std::max(db[i], loudest - 60.0f);
  speed.resize(static_cast<std::size_t>(covered));
  const int half = static_cast<int>(std::lround(smooth_s * fps / 2.0));
  return pearson(moving_average(speed, half), moving_average(loud, half));
}

std::vector<double> joint_mean_speeds(const Eigen::MatrixXd& pos, double fps) {
  const Eigen::MatrixXd rel = root_relative(pos);
  std::vector<double> out;
  for (Eigen::Index j = 0; j < pos.cols() / 3; ++j) {
    const std::vector<double> v = central_speed(rel, fps, j);
    out.push_back(v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size()));
  }
  return out;
}

double metric_bc_kinematic(const Eigen::MatrixXd& pos, double fps, const std::vector<int>& joints,
                           const std::vector<double>& mean_speed, const std::vector<double>& audio_beats_s,
                           const KinematicBeatParams& params) {
  if (joints.empty()) throw Error("kinematic beat consistency: no upper-body joints");
  if (params.order < 1 || !(params.sigma_s > 0.0)) throw Error("kinematic beat consistency: bad parameters");
  if (audio_beats_s.empty()) return 0.0;
  const Eigen::MatrixXd rel = root_relative(pos);
  const double two_sigma2 = 2.0 * params.sigma_s * params.sigma_s;
  double total = 0.0;
  for (int j : joints) {
    if (j < 0 || static_cast<std::size_t>(j) >= mean_speed.size())
      throw Error("kinematic beat consistency: no mean speed for joint " + std::to_string(j));
    std::vector<double> v = central_speed(rel, fps, j);
    const double scale = mean_speed[static_cast<std::size_t>(j)];
    for (double& x : v) x = scale > 0.0 ? x / scale : 0.0;
    std::vector<double> beats;
    const int n = static_cast<int>(v.size());
    for (int t = 0; t < n; ++t) {
      if (!(v[static_cast<std::size_t>(t)] > params.threshold)) continue;
      bool minimum = true;
      for (int k = 1; k <= params.order && minimum; ++k) {
        const int a = t - k, b = t + k;
        minimum = a >= 0 && b < n && v[static_cast<std::size_t>(t)] < v[static_cast<std::size_t>(a)] &&
                  v[static_cast<std::size_t>(t)] < v[static_cast<std::size_t>(b)];
      }
      if (minimum) beats.push_back(t / fps);
    }
    double sum = 0.0;
    if (!beats.empty())
      for (double b : audio_beats_s) {
        const auto it = std::lower_bound(beats.begin(), beats.end(), b);
        double d = std::numeric_limits<double>::infinity();
        if (it != beats.end()) d = *it - b;
        if (it != beats.begin()) d = std::min(d, b - *(it - 1));
        sum += std::exp(-d * d / two_sigma2);
      }
    total += sum / static_cast<double>(audio_beats_s.size());
  }
  return total / static_cast<double>(joints.size());
}

ControlledScore bc_controlled(const Eigen::MatrixXd& pos, double fps, const SyncControl& control,
                              const MetricParams& params) {
  const double duration = static_cast<double>(pos.rows()) / fps;
  ControlledScore s;
  s.aligned = metric_bc(pos, fps, control.aligned.onset_times_s, params);
  for (const SpeechTrack& t : control.shifted) s.shifted.push_back(metric_bc(pos, fps, t.onset_times_s, params));
  for (const SpeechTrack& t : control.mismatched)
    s.mismatched.push_back(metric_bc(pos, fps, beats_within(t.onset_times_s, duration), params));
  return s;
}

ControlledScore speech_correlation_controlled(const Eigen::MatrixXd& pos, double fps, const SyncControl& control) {
  ControlledScore s;
  s.aligned = metric_speech_correlation(pos, fps, control.aligned.envelope);
  for (const SpeechTrack& t : control.shifted) s.shifted.push_back(metric_speech_correlation(pos, fps, t.envelope));
  for (const SpeechTrack& t : control.mismatched)
    s.mismatched.push_back(metric_speech_correlation(pos, fps, t.envelope));
  return s;
}

ControlledScore energy_correlation_controlled(const Eigen::MatrixXd& pos, double fps, const std::vector<int>& joints,
                                              const SyncControl& control) {
  ControlledScore s;
  s.aligned = metric_energy_correlation(pos, fps, joints, control.aligned.energy);
  for (const SpeechTrack& t : control.shifted)
    s.shifted.push_back(metric_energy_correlation(pos, fps, joints, t.energy));
  for (const SpeechTrack& t : control.mismatched)
    s.mismatched.push_back(metric_energy_correlation(pos, fps, joints, t.energy));
  return s;
}

ControlledScore bc_kinematic_controlled(const Eigen::MatrixXd& pos, double fps, const std::vector<int>& joints,
                                        const std::vector<double>& mean_speed, const SyncControl& control) {
  const double duration = static_cast<double>(pos.rows()) / fps;
  auto bc = [&](const SpeechTrack& t) {
    return metric_bc_kinematic(pos, fps, joints, mean_speed, beats_within(t.beat_times_s, duration));
  };
  ControlledScore s;
  s.aligned = bc(control.aligned);
  for (const SpeechTrack& t : control.shifted) s.shifted.push_back(bc(t));
  for (const SpeechTrack& t : control.mismatched) s.mismatched.push_back(bc(t));
  return s;
}

}  // namespace gmg
