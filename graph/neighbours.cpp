#include "graph/neighbours.h"

#include <algorithm>
#include <limits>

#include "engine/core/parallel.h"
#include "graph/exact_finder.h"
#include "graph/tree_finder.h"

namespace gmg {
namespace {

// The candidate search's own bound on threads (see candidate_search_workers).
constexpr int kMaxCandidateWorkers = 4;

}  // namespace

NeighbourSearch neighbour_search_for(const GraphParams& params, int frames) {
  if (params.neighbours != NeighbourSearch::Auto) return params.neighbours;
  return frames <= params.exact_frames ? NeighbourSearch::Exact : NeighbourSearch::Approximate;
}

int candidate_search_workers() { return std::min(kMaxCandidateWorkers, worker_count(0)); }

int candidate_limit(const GraphParams& params) {
  if (params.max_transitions == 0) return 0;
  const long long k = static_cast<long long>(params.max_transitions) * params.candidates_per_transition;
  return static_cast<int>(std::min<long long>(k, std::numeric_limits<int>::max()));
}

std::unique_ptr<CandidateFinder> make_candidate_finder(const PoseFeatures& features, const std::vector<double>& theta,
                                                       const GraphParams& params, NeighbourSearch search, int workers) {
  workers = std::max(1, workers);
  if (search == NeighbourSearch::Auto) search = neighbour_search_for(params, features.frame_count());
  if (search == NeighbourSearch::Exact) return neighbours::make_exact_finder(features, theta, params, workers);
  return neighbours::make_tree_finder(features, theta, params, workers);
}

std::vector<std::vector<int>> candidate_sets(const PoseFeatures& features, const std::vector<double>& theta,
                                             const GraphParams& params, NeighbourSearch search) {
  const int n = features.frame_count();
  const std::unique_ptr<CandidateFinder> finder =
      make_candidate_finder(features, theta, params, search, candidate_search_workers());
  std::vector<std::vector<int>> all, block;
  for (int first = 0; first < n; first += finder->block_size()) {
    finder->next(first, std::min(finder->block_size(), n - first), block);
    for (auto& b : block) all.push_back(std::move(b));
  }
  return all;
}

double candidate_recall(const std::vector<std::vector<int>>& found, const std::vector<std::vector<int>>& exact) {
  std::size_t total = 0, hit = 0;
  for (std::size_t l = 0; l < exact.size(); ++l) {
    total += exact[l].size();
    if (l >= found.size()) continue;
    for (const int r : exact[l]) hit += std::binary_search(found[l].begin(), found[l].end(), r) ? 1 : 0;
  }
  return total == 0 ? 1.0 : static_cast<double>(hit) / static_cast<double>(total);
}

}  // namespace gmg
