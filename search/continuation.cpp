#include "search/continuation.h"

#include <cmath>

namespace gmg {

std::vector<int> natural_continuation(const MotionGraph& g, int from, const BeamRequest& request,
                                      const SearchParams& params) {
  const int target = std::max(1, request.target_length);
  const int min_len = std::max(2, static_cast<int>(std::ceil(params.continue_min * target - 1e-9)));
  const int max_len = static_cast<int>(std::floor(params.continue_max * target + 1e-9));
  int best = -1;
  double best_error = 0.0;
  for (int len = 2, f = from + 1; len <= max_len && f < g.frame_count(); ++len, ++f) {
    if (g.node(f - 1).kinds & kBreakNode) break;  // f is not f - 1's natural successor
    if (len < min_len || !is_stop_node(g, f, request)) continue;
    const double error = std::abs(1.0 - static_cast<double>(len) / target);
    if (best < 0 || error < best_error) {
      best = len;
      best_error = error;
    }
  }
  std::vector<int> path(static_cast<std::size_t>(std::max(best, 0)));
  for (int k = 0; k < best; ++k) path[static_cast<std::size_t>(k)] = from + k;
  return path;
}

std::vector<std::vector<int>> natural_continuations(const MotionGraph& g, int from, const BeamRequest& request,
                                                    const SearchParams& params) {
  const int target = std::max(1, request.target_length);
  const int min_len = std::max(2, static_cast<int>(std::ceil(params.continue_min * target - 1e-9)));
  const int max_len = static_cast<int>(std::floor(params.continue_max * target + 1e-9));
  std::vector<std::vector<int>> out;
  for (int len = 2, f = from + 1; len <= max_len && f < g.frame_count(); ++len, ++f) {
    if (g.node(f - 1).kinds & kBreakNode) break;  // f is not f - 1's natural successor
    if (len < min_len || !is_stop_node(g, f, request)) continue;
    std::vector<int> path(static_cast<std::size_t>(len));
    for (int k = 0; k < len; ++k) path[static_cast<std::size_t>(k)] = from + k;
    out.push_back(std::move(path));
  }
  return out;
}

std::vector<int> natural_run(const MotionGraph& g, int from, int length) {
  std::vector<int> path = {from};
  while (static_cast<int>(path.size()) < length && path.back() + 1 < g.frame_count() &&
         !(g.node(path.back()).kinds & kBreakNode))
    path.push_back(path.back() + 1);
  return path;
}

}  // namespace gmg
