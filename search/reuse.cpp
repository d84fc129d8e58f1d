#include "search/reuse.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gmg {

ReuseTracker::ReuseTracker(int frames, double halflife, int cap_plays, int cap_window, int return_window)
    : frames_(std::max(0, frames)),
      decay_per_frame_(std::log(2.0) / std::max(1e-9, halflife)),
      cap_plays_(std::max(0, cap_plays)),
      cap_window_(std::max(0, cap_window)),
      return_window_(std::max(0, return_window)),
      blocks_(static_cast<std::size_t>(frames_ / kBlock + 1)) {}

ReuseTracker::Block& ReuseTracker::block_to_play(int f) {
  std::unique_ptr<Block>& b = blocks_[static_cast<std::size_t>(f / kBlock)];
  if (!b) {
    b = std::make_unique<Block>();
    b->count.assign(kBlock, 0.0);
    b->last.assign(kBlock, 0);
    // Never played: a time so early that no window reaches it.
    b->recent.assign(static_cast<std::size_t>(kBlock) * static_cast<std::size_t>(cap_plays_),
                     std::numeric_limits<int>::min() / 2);
  }
  return *b;
}

double ReuseTracker::plays(int f, int time) const {
  const Block* b = block(f);
  const std::size_t k = static_cast<std::size_t>(f % kBlock);
  if (!b || b->count[k] == 0.0) return 0.0;
  return b->count[k] * std::exp(-decay_per_frame_ * std::max(0, time - b->last[k]));
}

void ReuseTracker::play(const std::vector<int>& path, int time) {
  int previous = -1;
  for (int f : path) {
    if (f == previous) continue;  // a held frame is one play
    const double p = plays(f, time);
    Block& b = block_to_play(f);
    const std::size_t k = static_cast<std::size_t>(f % kBlock);
    b.count[k] = p + 1.0;
    b.last[k] = time;
    if (cap_plays_ > 0) {
      int* times = b.recent.data() + k * static_cast<std::size_t>(cap_plays_);
      std::copy(times + 1, times + cap_plays_, times);
      times[cap_plays_ - 1] = time;
    }
    previous = f;
  }
}

double ReuseTracker::path_cost(const std::vector<int>& path, int time) const {
  double worst = 0.0;
  for (int f : path) worst = std::max(worst, frame_cost(f, time));
  // A loop plays a frame twice within seconds: a jump back, and plays the tracker cannot see yet.
  if ((return_window_ > 0 || cap_plays_ > 0) && loops(path)) worst += kCapCost;
  return worst;
}

bool ReuseTracker::loops(const std::vector<int>& path) {
  std::vector<int> frames;
  for (std::size_t i = 0; i < path.size(); ++i)
    if (i == 0 || path[i] != path[i - 1]) frames.push_back(path[i]);
  std::sort(frames.begin(), frames.end());
  return std::adjacent_find(frames.begin(), frames.end()) != frames.end();
}

void ReuseTracker::window_costs(int window, int time, const std::vector<int>& frames, std::vector<double>& out) const {
  out.assign(frames.size(), 0.0);
  if (window < 1 || frames_ == 0) return;
  const int last = frames_ - 1;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    // A window whose frames lie in blocks never played costs 0 (most windows of a long reference).
    const int from = std::min(frames[k], last), to = std::min(frames[k] + window - 1, last);
    if (to - from < kBlock && !block(from) && !block(to)) continue;
    double worst = 0.0;
    for (int i = 0; i < window; ++i) worst = std::max(worst, frame_cost(std::min(frames[k] + i, last), time));
    out[k] = worst;
  }
}

}  // namespace gmg
