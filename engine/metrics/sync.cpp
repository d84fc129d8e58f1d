#include "engine/metrics/sync.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "audio/onset.h"
#include "engine/core/error.h"
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
  return {a.onset_times(), a.envelope};
}

SyncControl sync_control(const audio::Audio& sound, int count, double min_shift_s) {
  SyncControl c;
  c.shifts_s = control_shifts(sound.duration(), count, min_shift_s);
  c.aligned = speech_track(sound);
  for (double s : c.shifts_s) c.shifted.push_back(speech_track(circular_shift(sound, s)));
  return c;
}

double ControlledScore::shifted_mean() const {
  return shifted.empty() ? 0.0 : std::accumulate(shifted.begin(), shifted.end(), 0.0) / shifted.size();
}

double ControlledScore::shifted_sd() const {
  if (shifted.size() < 2) return 0.0;
  const double m = shifted_mean();
  double ss = 0.0;
  for (double x : shifted) ss += (x - m) * (x - m);
  return std::sqrt(ss / (shifted.size() - 1));
}

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

// Centred moving average over 2 * half + 1 samples, shrunk at the ends.
std::vector<double> moving_average(const std::vector<double>& x, int half) {
  std::vector<double> y(x.size());
  const int n = static_cast<int>(x.size());
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    int count = 0;
    for (int k = std::max(0, i - half); k <= std::min(n - 1, i + half); ++k, ++count)
      sum += x[static_cast<std::size_t>(k)];
    y[static_cast<std::size_t>(i)] = sum / count;
  }
  return y;
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

ControlledScore bc_controlled(const Eigen::MatrixXd& pos, double fps, const SyncControl& control,
                              const MetricParams& params) {
  ControlledScore s;
  s.aligned = metric_bc(pos, fps, control.aligned.onset_times_s, params);
  for (const SpeechTrack& t : control.shifted) s.shifted.push_back(metric_bc(pos, fps, t.onset_times_s, params));
  return s;
}

ControlledScore speech_correlation_controlled(const Eigen::MatrixXd& pos, double fps, const SyncControl& control) {
  ControlledScore s;
  s.aligned = metric_speech_correlation(pos, fps, control.aligned.envelope);
  for (const SpeechTrack& t : control.shifted) s.shifted.push_back(metric_speech_correlation(pos, fps, t.envelope));
  return s;
}

}  // namespace gmg
