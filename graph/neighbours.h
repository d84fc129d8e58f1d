// Candidate transitions (paper 4.1.2; SPEC "Edges"), bounded: the frames a frame may jump to.
//
// The candidate set of frame l is K_l: the k frames r nearest to l by d(l, r) (ties: lower r
// first) among those with d(l, r) <= theta_l and r allowed (r != l, r != l + 1, and
// |r - l| > l_pn unless exclude_near is off), where k = candidates_per_transition *
// max_transitions; with max_transitions 0, K_l holds them all (the paper's candidates).
//
// Two searches find it, both in the pose space of graph/pose_space.h and gathering through
// graph/candidate_gathering.h:
// - exact (graph/exact_finder.cpp): every pair's distance is bounded from below by
//   principal-axis projections of the positions and velocities (one matrix product per tile of
//   pairs, each tile serving both directions since d(l, r) = d(r, l)); only pairs whose bound is
//   within reach get d. Time grows as frames^2, memory linearly.
// - approximate (graph/tree_finder.cpp): a k-d tree over the same projections, searched best
//   first with the same lower bound, refined by d. Run to the end (ann_checks 0) it is exact; with
//   ann_checks it stops after that many distance evaluations per frame (time ~ frames *
//   log(frames)).
// Distances are screened in single precision; any decision within float error of a threshold or
// of the k-th distance is taken on d in double, so both searches give the same K_l exactly.
#pragma once

#include <memory>
#include <vector>

#include "graph/features.h"
#include "graph/params.h"

namespace gmg {

// The search `params.neighbours` asks for with `frames` frames (Auto resolved).
NeighbourSearch neighbour_search_for(const GraphParams& params, int frames);

// K_l's size bound (see above); 0 = unbounded.
int candidate_limit(const GraphParams& params);

// Finds K_l for consecutive blocks of frames, in order: next(first, count) with first = 0, then
// the previous first + count, and so on. Blocks are computed by `workers` threads.
class CandidateFinder {
 public:
  virtual ~CandidateFinder() = default;
  // out[i] = K_{first + i}, ascending.
  virtual void next(int first, int count, std::vector<std::vector<int>>& out) = 0;
  // Frames per block the finder works best with.
  virtual int block_size() const = 0;
};

// The threads the candidate search runs on: one per hardware thread (engine/core/parallel.h),
// at most 4 (every worker keeps its own gathering of a block's left frames, merged after the
// pass).
int candidate_search_workers();

// theta[l] is frame l's threshold (graph/continuity.h). `features` and `theta` must outlive the
// finder.
std::unique_ptr<CandidateFinder> make_candidate_finder(const PoseFeatures& features, const std::vector<double>& theta,
                                                       const GraphParams& params, NeighbourSearch search, int workers);

// K_l of every frame with the given search (for tests and recall measurements).
std::vector<std::vector<int>> candidate_sets(const PoseFeatures& features, const std::vector<double>& theta,
                                             const GraphParams& params, NeighbourSearch search);

// Share of `exact`'s members (frame pairs) that `found` also holds: the recall of an
// approximate search. 1 when `exact` is empty.
double candidate_recall(const std::vector<std::vector<int>>& found, const std::vector<std::vector<int>>& exact);

}  // namespace gmg
