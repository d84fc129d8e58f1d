#include "graph/pruning.h"

#include <algorithm>
#include <string>

#include "engine/core/error.h"

namespace gmg {

namespace {

// Calls keep(i) for the kept items of a list sorted by frame (frame(i) its i-th frame).
template <typename Frame, typename Keep>
void each_kept(std::size_t n, int l_pn, const Frame& frame, const Keep& keep) {
  int run_position = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0 && frame(i) == frame(i - 1) + 1)
      ++run_position;
    else
      run_position = 0;
    if (run_position % l_pn == 0) keep(i);
  }
}

}  // namespace

std::vector<int> prune_runs(const std::vector<int>& candidates, int l_pn) {
  std::vector<int> kept;
  each_kept(
      candidates.size(), l_pn, [&](std::size_t i) { return candidates[i]; },
      [&](std::size_t i) { kept.push_back(candidates[i]); });
  return kept;
}

void prune_runs(const std::vector<Candidate>& candidates, int l_pn, std::vector<Candidate>& out) {
  each_kept(
      candidates.size(), l_pn, [&](std::size_t i) { return candidates[i].r; },
      [&](std::size_t i) { out.push_back(candidates[i]); });
}

void EdgeIndex::add(int a, int b) {
  if (a < 0 || a >= frames_ || static_cast<std::size_t>(a) + 1 < first_.size())
    throw Error("EdgeIndex: edge from frame " + std::to_string(a) + " after frame " +
                std::to_string(static_cast<long>(first_.size()) - 1) + " or outside 0.." + std::to_string(frames_ - 1));
  while (first_.size() <= static_cast<std::size_t>(a)) first_.push_back(targets_.size());
  targets_.push_back(b);
}

bool EdgeIndex::any(int a_lo, int a_hi, int b_lo, int b_hi) const {
  // One binary search per source in range: its targets are ascending.
  const int last = static_cast<int>(first_.size()) - 1;
  for (int a = std::max(0, a_lo); a <= std::min(last, a_hi); ++a) {
    const std::size_t fa = static_cast<std::size_t>(a);
    const auto begin = targets_.begin() + static_cast<std::ptrdiff_t>(first_[fa]);
    const auto end = a < last ? targets_.begin() + static_cast<std::ptrdiff_t>(first_[fa + 1]) : targets_.end();
    const auto it = std::lower_bound(begin, end, b_lo);
    if (it != end && *it <= b_hi) return true;
  }
  return false;
}

}  // namespace gmg
