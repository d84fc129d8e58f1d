#include "search/reuse.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gmg {

ReuseTracker::ReuseTracker(int frames, double halflife, int cap_plays, int cap_window)
    : count_(static_cast<std::size_t>(std::max(0, frames)), 0.0),
      last_(count_.size(), 0),
      decay_per_frame_(std::log(2.0) / std::max(1e-9, halflife)),
      cap_plays_(std::max(0, cap_plays)),
      cap_window_(std::max(0, cap_window)),
      // Never played: a time so early that no window reaches it.
      recent_(count_.size() * static_cast<std::size_t>(cap_plays_), std::numeric_limits<int>::min() / 2) {}

double ReuseTracker::plays(int f, int time) const {
  const std::size_t k = static_cast<std::size_t>(f);
  if (count_[k] == 0.0) return 0.0;
  return count_[k] * std::exp(-decay_per_frame_ * std::max(0, time - last_[k]));
}

void ReuseTracker::play(const std::vector<int>& path, int time) {
  int previous = -1;
  for (int f : path) {
    if (f == previous) continue;  // a held frame is one play
    const std::size_t k = static_cast<std::size_t>(f);
    count_[k] = plays(f, time) + 1.0;
    last_[k] = time;
    if (cap_plays_ > 0) {
      int* times = recent_.data() + k * static_cast<std::size_t>(cap_plays_);
      std::copy(times + 1, times + cap_plays_, times);
      times[cap_plays_ - 1] = time;
    }
    previous = f;
  }
}

double ReuseTracker::path_cost(const std::vector<int>& path, int time) const {
  double worst = 0.0;
  for (int f : path) worst = std::max(worst, frame_cost(f, time));
  return worst;
}

void ReuseTracker::window_costs(int window, int time, const std::vector<int>& frames, std::vector<double>& out) const {
  out.assign(frames.size(), 0.0);
  if (window < 1 || count_.empty()) return;
  const int last = static_cast<int>(count_.size()) - 1;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    double worst = 0.0;
    for (int i = 0; i < window; ++i) worst = std::max(worst, frame_cost(std::min(frames[k] + i, last), time));
    out[k] = worst;
  }
}

}  // namespace gmg
