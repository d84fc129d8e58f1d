#include "graph/neighbours.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/parallel.h"
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

long search_checks(const GraphParams& params, int frames, NeighbourSearch search) {
  if (search == NeighbourSearch::Auto) {
    if (neighbour_search_for(params, frames) == NeighbourSearch::Exact) return 0;
    if (frames <= kAnnChecksFrames || params.ann_checks == 0) return params.ann_checks;
    const double doublings = std::log2(static_cast<double>(frames) / kAnnChecksFrames);
    return std::lround(params.ann_checks * (1.0 + kAnnChecksGrowth * doublings));
  }
  return search == NeighbourSearch::Exact ? 0 : params.ann_checks;
}

int candidate_search_workers() { return std::min(kMaxCandidateWorkers, worker_count(0)); }

int candidate_limit(const GraphParams& params) {
  if (params.max_transitions == 0) return 0;
  const long long k = static_cast<long long>(params.max_transitions) * params.candidates_per_transition;
  return static_cast<int>(std::min<long long>(k, std::numeric_limits<int>::max()));
}

CandidateSearch::CandidateSearch(neighbours::PoseSpace&& space, const std::vector<double>& theta,
                                 const GraphParams& params, NeighbourSearch search) {
  const long checks = search_checks(params, space.frames(), search);
  tree_ = std::make_unique<neighbours::CandidateTree>(std::move(space), theta, params, checks);
}

CandidateSearch::CandidateSearch(const PoseFeatures& features, const std::vector<double>& theta,
                                 const GraphParams& params, NeighbourSearch search)
    : CandidateSearch(neighbours::PoseSpace(features, params), theta, params, search) {}

CandidateSearch::~CandidateSearch() = default;

int CandidateSearch::frames() const { return tree_->frames(); }

const std::vector<int>& CandidateSearch::query_order() const { return tree_->order(); }

void CandidateSearch::find(int l, CandidateScratch& scratch, std::vector<Candidate>& out) const {
  tree_->find(l, scratch, out);
}

void CandidateSearch::find_run(int first, int count, std::vector<CandidateScratch>& scratch,
                               std::vector<std::vector<Candidate>>& out) const {
  tree_->find_run(first, count, scratch, out);
}

float CandidateSearch::error(float d) const { return tree_->space().error(d); }

double CandidateSearch::distance(int l, int r) const { return tree_->space().exact(l, r); }

const FeatureStore& CandidateSearch::store() const { return tree_->space().store(); }

std::vector<std::vector<int>> candidate_sets(const PoseFeatures& features, const std::vector<double>& theta,
                                             const GraphParams& params, NeighbourSearch search) {
  const CandidateSearch finder(features, theta, params, search);
  const int n = finder.frames();
  std::vector<std::vector<int>> all(static_cast<std::size_t>(n));
  const int workers = candidate_search_workers();
  // Runs of the tree's order, as the continuity analysis takes them.
  constexpr int kRun = 64;
  std::vector<std::vector<CandidateScratch>> scratch(static_cast<std::size_t>(workers));
  std::vector<std::vector<std::vector<Candidate>>> found(static_cast<std::size_t>(workers));
  const std::vector<int>& order = finder.query_order();
  parallel_for(static_cast<std::size_t>((n + kRun - 1) / kRun), workers, [&](std::size_t run, int worker) {
    const int first = static_cast<int>(run) * kRun, count = std::min(kRun, n - first);
    std::vector<std::vector<Candidate>>& k = found[static_cast<std::size_t>(worker)];
    finder.find_run(first, count, scratch[static_cast<std::size_t>(worker)], k);
    for (int i = 0; i < count; ++i)
      for (const Candidate& c : k[static_cast<std::size_t>(i)])
        all[static_cast<std::size_t>(order[static_cast<std::size_t>(first + i)])].push_back(c.r);
  });
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
