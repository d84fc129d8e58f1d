#include "graph/pruning.h"

#include <algorithm>

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

bool EdgeIndex::any(int a_lo, int a_hi, int b_lo, int b_hi) const {
  // One binary search per source in range: its targets are ascending.
  const int n = static_cast<int>(targets_.size());
  for (int a = std::max(0, a_lo); a <= std::min(n - 1, a_hi); ++a) {
    const std::vector<int>& t = targets_[static_cast<std::size_t>(a)];
    const auto it = std::lower_bound(t.begin(), t.end(), b_lo);
    if (it != t.end() && *it <= b_hi) return true;
  }
  return false;
}

}  // namespace gmg
