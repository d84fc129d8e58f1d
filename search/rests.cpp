#include "search/rests.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "audio/speech_features.h"
#include "graph/reference_facts.h"

namespace gmg {

RestFinder::RestFinder(const MotionGraph& g) {
  const int n = g.frame_count();
  if (g.activity.size() != static_cast<std::size_t>(n) || n < 2) return;
  runs_ = graph_runs(g);
  prefix_.assign(static_cast<std::size_t>(n) + 1, 0.0);
  std::vector<float> sorted(static_cast<std::size_t>(n));
  for (int f = 0; f < n; ++f) {
    prefix_[static_cast<std::size_t>(f) + 1] =
        prefix_[static_cast<std::size_t>(f)] + g.activity[static_cast<std::size_t>(f)];
    sorted[static_cast<std::size_t>(f)] = g.activity[static_cast<std::size_t>(f)];
  }
  const auto q = sorted.begin() + static_cast<std::ptrdiff_t>(kStillQuantile * (n - 1));
  std::nth_element(sorted.begin(), q, sorted.end());
  const float still = *q;
  int run = 0;
  for (int f = 0; f < n; ++f) {
    run = g.activity[static_cast<std::size_t>(f)] <= still ? (f > 0 && runs_.continues(f - 1) ? run : 0) + 1 : 0;
    hold_ = std::max(hold_, run);
  }
  if (g.has_speech() && g.speech.size() >= static_cast<std::size_t>(n) * static_cast<std::size_t>(g.speech_dims)) {
    pause_.assign(static_cast<std::size_t>(n) + 1, 0.0);
    for (int f = 0; f < n; ++f)
      pause_[static_cast<std::size_t>(f) + 1] =
          pause_[static_cast<std::size_t>(f)] + audio::pause_weight(g.speech_at(f)[0]);
  }
  motion_release_pages(g.motion);
}

double RestFinder::pause_share(int f, int length) const {
  if (pause_.empty()) return 1.0;
  if (length < 1 || f < 0 || f + length > runs_.frame_count() || runs_.last(f) < f + length - 1) return 0.0;
  return (pause_[static_cast<std::size_t>(f + length)] - pause_[static_cast<std::size_t>(f)]) / length;
}

double RestFinder::stillness(int f, int length) const {
  if (prefix_.empty() || length < 1 || f < 0 || f + length > runs_.frame_count() || runs_.last(f) < f + length - 1)
    return std::numeric_limits<double>::infinity();
  return (prefix_[static_cast<std::size_t>(f + length)] - prefix_[static_cast<std::size_t>(f)]) / length;
}

std::vector<int> RestFinder::stillest(int length, int count) const { return stillest_where(length, count, false); }

std::vector<int> RestFinder::stillest_pauses(int length, int count) const {
  return pause_.empty() ? std::vector<int>{} : stillest_where(length, count, true);
}

std::vector<int> RestFinder::stillest_where(int length, int count, bool in_pauses) const {
  std::vector<std::pair<double, int>> all;
  for (int f = 0; f + length <= runs_.frame_count(); ++f) {
    if (in_pauses && pause_share(f, length) < 0.5) continue;
    const double s = stillness(f, length);
    if (s < std::numeric_limits<double>::infinity()) all.push_back({s, f});
  }
  const std::size_t keep = std::min(all.size(), static_cast<std::size_t>(std::max(0, count)));
  std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(keep), all.end());
  std::vector<int> out;
  for (std::size_t i = 0; i < keep; ++i) out.push_back(all[i].second);
  return out;
}

}  // namespace gmg
