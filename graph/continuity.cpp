#include "graph/continuity.h"

#include <algorithm>
#include <cmath>
#include <future>

#include "engine/core/error.h"
#include "graph/neighbours.h"
#include "graph/pruning.h"

namespace gmg {

std::vector<double> continuity_thresholds(const PoseFeatures& f, const std::vector<int>& run_end,
                                          const GraphParams& params) {
  const int n = f.frame_count();
  std::vector<double> theta(static_cast<std::size_t>(n), 0.0);
  for (int l = 0; l < n; ++l) {
    const int end = run_end[static_cast<std::size_t>(l)];
    double sum = 0.0;
    int count = 0;
    for (int k = 1; k <= params.l_cn && l + k <= end; ++k, ++count) sum += pose_distance(f, l, l + k, params);
    if (count == 0) {
      for (int k = 1; k <= params.l_cn && l - k >= 0 && run_end[static_cast<std::size_t>(l - k)] == end; ++k, ++count)
        sum += pose_distance(f, l, l - k, params);
    }
    theta[static_cast<std::size_t>(l)] = count > 0 ? sum / count : 0.0;
  }
  return theta;
}

namespace {

// Pruning 1 on the frame's candidates, pruning 2 against the edges so far, then the
// max_transitions nearest survivors (by weight, then target), by ascending target.
void transitions_of(int l, const std::vector<int>& candidates, const PoseFeatures& f, const GraphParams& params,
                    const EdgeIndex& index, std::vector<Transition>& edges) {
  const std::size_t first = edges.size();
  for (const int r : prune_runs(candidates, params.l_pn)) {
    if (index.covers(l, r, params.l_pn)) continue;
    edges.push_back({l, r, pose_distance(f, l, r, params)});
  }
  const std::size_t limit = static_cast<std::size_t>(params.max_transitions);
  if (limit == 0 || edges.size() - first <= limit) return;
  const auto begin = edges.begin() + static_cast<std::ptrdiff_t>(first);
  const auto keep = begin + static_cast<std::ptrdiff_t>(limit);
  std::partial_sort(begin, keep, edges.end(), [](const Transition& a, const Transition& b) {
    return a.weight < b.weight || (a.weight == b.weight && a.to < b.to);
  });
  edges.erase(keep, edges.end());
  std::sort(begin, edges.end(), [](const Transition& a, const Transition& b) { return a.to < b.to; });
}

}  // namespace

std::vector<Transition> continuity_analysis(const PoseFeatures& f, const std::vector<int>& run_end,
                                            const GraphParams& params, const ContinuityProgress& progress) {
  const int n = f.frame_count();
  if (static_cast<int>(run_end.size()) != n) throw Error("continuity_analysis: run_end has the wrong size");
  std::vector<Transition> edges;
  if (n < 2) return edges;
  const std::vector<double> theta = continuity_thresholds(f, run_end, params);
  const std::unique_ptr<CandidateFinder> finder =
      make_candidate_finder(f, theta, params, neighbour_search_for(params, n), candidate_search_workers());
  const int step = finder->block_size();
  if (params.max_transitions > 0)
    edges.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(std::min(params.max_transitions, 8)));

  EdgeIndex index(n);
  using Lists = std::vector<std::vector<int>>;
  // Candidates of a block are found (in parallel) while pruning 2, which depends on the edges
  // of earlier left frames, walks the previous block in order on this thread.
  auto compute = [&](int block) {
    Lists lists;
    finder->next(block, std::min(step, n - block), lists);
    return lists;
  };
  std::future<Lists> next = std::async(std::launch::async, compute, 0);
  for (int block = 0; block < n; block += step) {
    const Lists candidates = next.get();
    if (block + step < n) next = std::async(std::launch::async, compute, block + step);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const int l = block + static_cast<int>(i);
      const std::size_t first = edges.size();
      transitions_of(l, candidates[i], f, params, index, edges);
      // Pruning 2 looks only at earlier left frames: this frame's edges join the index after
      // all of its candidates were tested.
      for (std::size_t e = first; e < edges.size(); ++e) index.add(l, edges[e].to);  // ascending
    }
    if (progress) progress(std::min(n, block + step), n);
  }
  return edges;
}

}  // namespace gmg
