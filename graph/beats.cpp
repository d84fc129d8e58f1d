#include "graph/beats.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace gmg {

std::vector<float> beat_end_costs(const Samples<float>& activity, const CaptureRuns& runs, double fps) {
  const int n = runs.frame_count();
  if (activity.size() != static_cast<std::size_t>(n)) throw Error("beats: the activity does not cover the frames");
  const Samples<float>& a = activity;
  std::vector<int> beats;
  for (int f = 0; f < n; ++f) {
    if (!(a[static_cast<std::size_t>(f)] > kBeatMinActivity)) continue;
    bool minimum = true;
    const int last = runs.last(f);
    for (int k = 1; k <= kBeatOrder && minimum; ++k) {
      const int lo = f - k, hi = f + k;
      minimum = lo >= 0 && hi <= last && runs.last(lo) == last &&
                a[static_cast<std::size_t>(f)] < a[static_cast<std::size_t>(lo)] &&
                a[static_cast<std::size_t>(f)] < a[static_cast<std::size_t>(hi)];
    }
    if (minimum) beats.push_back(f);
  }
  std::vector<float> out(static_cast<std::size_t>(n), 1.0f);
  const double two_sigma2 = 2.0 * (kBeatSigmaS * fps) * (kBeatSigmaS * fps);
  std::size_t b = 0;
  for (int f = 0; f < n; ++f) {
    while (b + 1 < beats.size() && beats[b + 1] <= f) ++b;
    double d = 1e9;
    for (std::size_t k = b; k < std::min(beats.size(), b + 2); ++k)
      if (runs.last(beats[k]) == runs.last(f)) d = std::min(d, std::abs(static_cast<double>(beats[k] - f)));
    out[static_cast<std::size_t>(f)] = static_cast<float>(1.0 - std::exp(-d * d / two_sigma2));
  }
  return out;
}

}  // namespace gmg
