#include "graph/pruning.h"

#include <algorithm>

namespace gmg {

std::vector<int> prune_runs(const std::vector<int>& candidates, int l_pn) {
  std::vector<int> kept;
  int run_position = 0;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (i > 0 && candidates[i] == candidates[i - 1] + 1)
      ++run_position;
    else
      run_position = 0;
    if (run_position % l_pn == 0) kept.push_back(candidates[i]);
  }
  return kept;
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
