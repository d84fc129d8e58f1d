// Peak picking and backtracking on the onset strength envelope, after librosa 0.10.2.
#include "audio/onset.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <string>
#include <utility>

#include "engine/core/error.h"

namespace gmg::audio {

std::vector<double> OnsetAnalysis::onset_times() const {
  std::vector<double> t;
  t.reserve(onset_frames.size());
  for (int f : onset_frames) t.push_back(static_cast<double>(f) * kHop / kSampleRate);
  return t;
}

OnsetAnalysis detect_onsets_in_envelope(const std::vector<float>& envelope, const OnsetParams& params) {
  if (params.pre_max < 0 || params.post_max < 1 || params.pre_avg < 0 || params.post_avg < 1 || params.wait < 0) {
    throw Error(
        "onset detection: invalid peak-picking parameters (pre_max, pre_avg, wait >= 0; post_max, post_avg >= 1)");
  }
  OnsetAnalysis a;
  a.envelope = envelope;
  const long long n = static_cast<long long>(envelope.size());
  if (n == 0) return a;

  // onset_detect's normalisation, in float32 as librosa does it:
  // x = env - min(env); x /= max(x) + tiny.
  const float mn = *std::min_element(envelope.begin(), envelope.end());
  std::vector<float> x(envelope.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = envelope[i] - mn;
  const float mx = *std::max_element(x.begin(), x.end());
  bool any = false, finite = true;
  for (float& v : x) {
    v /= (mx + FLT_MIN);
    any = any || v != 0.0f;
    finite = finite && std::isfinite(v);
  }
  if (!any || !finite) return a;  // onset_detect: nothing to pick

  // librosa.util.peak_pick (0.10): x[i] is a peak when it equals the max of
  // x[i - pre_max, i + post_max) and is >= mean(x[i - pre_avg, i + post_avg))
  // + delta, both windows truncated at the ends; after a peak the next `wait`
  // frames are skipped (greedy from the left).
  std::vector<int> peaks;
  long long i = 0;
  while (i < n) {
    const long long a0 = std::max(0LL, i - params.pre_max), a1 = std::min(n, i + params.post_max);
    const float maxn = *std::max_element(x.begin() + a0, x.begin() + a1);
    if (x[static_cast<std::size_t>(i)] == maxn) {
      const long long b0 = std::max(0LL, i - params.pre_avg), b1 = std::min(n, i + params.post_avg);
      double sum = 0.0;
      for (long long j = b0; j < b1; ++j) sum += x[static_cast<std::size_t>(j)];
      if (x[static_cast<std::size_t>(i)] >= sum / static_cast<double>(b1 - b0) + params.delta) {
        peaks.push_back(static_cast<int>(i));
        i += params.wait + 1;
        continue;
      }
    }
    ++i;
  }

  // Keep the peaks whose raw strength reaches the threshold.
  for (int p : peaks) {
    const float s = envelope[static_cast<std::size_t>(p)];
    if (static_cast<double>(s) >= params.min_onset_strength) {
      a.peak_frames.push_back(p);
      a.peak_strengths.push_back(s);
    }
  }

  // librosa.onset.onset_backtrack: minima are frames i in 1..n-2 with
  // env[i] <= env[i-1] and env[i] < env[i+1], plus frame 0; each event goes
  // to the last minimum at or before it.
  std::vector<int> minima{0};
  for (long long j = 1; j + 1 < n; ++j) {
    const float e = envelope[static_cast<std::size_t>(j)];
    if (e <= envelope[static_cast<std::size_t>(j - 1)] && e < envelope[static_cast<std::size_t>(j + 1)]) {
      minima.push_back(static_cast<int>(j));
    }
  }
  for (int p : a.peak_frames) {
    auto it = std::upper_bound(minima.begin(), minima.end(), p);  // first minimum > p
    a.onset_frames.push_back(*(it - 1));                          // minima[0] = 0 <= p
  }
  return a;
}

OnsetAnalysis detect_onsets(const Audio& audio, const OnsetParams& params) {
  return detect_onsets_in_envelope(onset_strength_envelope(audio), params);
}

OnsetAnalysis detect_onsets(Audio&& audio, const OnsetParams& params) {
  return detect_onsets_in_envelope(onset_strength_envelope(std::move(audio)), params);
}

std::vector<int> onset_motion_frames(const OnsetAnalysis& a, double fps, int num_frames) {
  std::vector<int> out;
  if (num_frames <= 0 || !(fps > 0.0)) return out;
  for (double t : a.onset_times()) {
    const long long f = std::llround(t * fps);
    if (f >= 0 && f < num_frames) out.push_back(static_cast<int>(f));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace gmg::audio
