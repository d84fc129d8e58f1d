// Candidate transitions (paper 4.1.2; SPEC "Edges"), bounded: the frames a frame may jump to.
//
// The candidate set of frame l is K_l: the k frames r nearest to l by d(l, r) (ties: lower r
// first) among those with d(l, r) <= theta_l and r allowed (r != l, r != l + 1, and
// |r - l| > l_pn unless exclude_near is off), where k = candidates_per_transition *
// max_transitions; with max_transitions 0, K_l holds them all (the paper's candidates).
//
// One search finds it (graph/tree_finder.h): a k-d tree over principal-axis projections of the
// pose space (graph/pose_space.h), whose boxes and points bound d from below, searched best first
// and refined by d. Searched to the end (NeighbourSearch::Exact) it finds K_l exactly. With a
// budget (Approximate: ann_checks frames per frame; under Auto a budget that grows with the log of
// the length, search_checks) the 16 frames of each leaf of the tree are searched together, by one
// walk that examines at most kLeafWalkChecks times the budget (graph/params.h): its time per frame
// grows little with the reference, and it misses a few far members (0.99 of the exact pairs on a
// synthetic speaker of 4 h; docs/performance.md). Either way a frame's K_l does not depend on which
// other frames are asked for with it, nor on the threads.
// Distances are screened in single precision; any decision within float error of a threshold or
// of the k-th distance is taken on d in double, so the exact search gives K_l exactly.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "graph/features.h"
#include "graph/params.h"

namespace gmg {

namespace neighbours {
class CandidateTree;
class PoseSpace;
}  // namespace neighbours

// The search `params.neighbours` asks for with `frames` frames (Auto resolved).
NeighbourSearch neighbour_search_for(const GraphParams& params, int frames);

// Frames the search examines per frame at most for `frames` frames (0: to the end, exact):
// Exact 0, Approximate params.ann_checks, Auto 0 up to params.exact_frames and above it
// params.ann_checks grown past kAnnChecksFrames as graph/params.h says.
long search_checks(const GraphParams& params, int frames, NeighbourSearch search);

// K_l's size bound (see above); 0 = unbounded.
int candidate_limit(const GraphParams& params);

// The threads the candidate search runs on: one per hardware thread (engine/core/parallel.h), at
// most 4.
int candidate_search_workers();

// A member r of K_l and d(l, r) in single precision (within CandidateSearch::error of d).
struct Candidate {
  float d;
  int r;
};

// A tree node to visit and the lower bound of d over its box.
struct OpenNode {
  float bound;
  int node;
};

// One thread's working memory for CandidateSearch::find (reused across calls).
struct CandidateScratch {
  std::vector<OpenNode> open;                // tree nodes to visit, by lower bound (a min-heap)
  std::vector<float> kth;                    // the k smallest member distances so far (a max-heap)
  std::vector<Candidate> items;              // the members so far
  std::vector<std::pair<double, int>> ties;  // members within float error of the k-th, in double
  // A budgeted find's: the scratch and the candidates of every frame of the frame's leaf.
  std::vector<CandidateScratch> leaf;
  std::vector<std::vector<Candidate>> leaf_found;
};

// K_l of any frame, from any thread (const; each thread brings its own scratch). `features`,
// `theta` and `params` must outlive it.
class CandidateSearch {
 public:
  // theta[l] is frame l's threshold (graph/continuity.h); search is Exact or Approximate (Auto is
  // resolved with neighbour_search_for). The search takes the pose space (graph/pose_space.h).
  CandidateSearch(neighbours::PoseSpace&& space, const std::vector<double>& theta, const GraphParams& params,
                  NeighbourSearch search);
  // The same over features in memory.
  CandidateSearch(const PoseFeatures& features, const std::vector<double>& theta, const GraphParams& params,
                  NeighbourSearch search);
  ~CandidateSearch();
  CandidateSearch(const CandidateSearch&) = delete;
  CandidateSearch& operator=(const CandidateSearch&) = delete;

  int frames() const;
  // Every frame once, in the tree's order: queries taken in this order read the same few nodes and
  // leaves one after another (a frame's neighbours are its neighbours' too), where frame order
  // jumps across the whole tree at every query.
  const std::vector<int>& query_order() const;
  // out = K_l by ascending r, each with d(l, r) in single precision. (With a budget, this searches
  // the frames of l's whole leaf: ask for many frames with find_run.)
  void find(int l, CandidateScratch& scratch, std::vector<Candidate>& out) const;
  // out[i] = K_l of frame query_order()[first + i], i < count, as find gives it; the search takes 16
  // neighbouring frames at a time together, sharing their walk through the tree (with a budget, the
  // frames of a leaf: runs that start at a multiple of 16 waste nothing). `scratch` is one thread's
  // (grown as needed); out grows to at least count.
  void find_run(int first, int count, std::vector<CandidateScratch>& scratch,
                std::vector<std::vector<Candidate>>& out) const;
  // An upper bound of |float d - d| for distances up to d.
  float error(float d) const;
  // d(l, r) in double (graph/features.h).
  double distance(int l, int r) const;
  // The feature store the distances come from.
  const FeatureStore& store() const;

 private:
  std::unique_ptr<neighbours::CandidateTree> tree_;
};

// K_l of every frame with the given search, as frame lists (for tests and recall measurements).
std::vector<std::vector<int>> candidate_sets(const PoseFeatures& features, const std::vector<double>& theta,
                                             const GraphParams& params, NeighbourSearch search);

// Share of `exact`'s members (frame pairs) that `found` also holds: the recall of an
// approximate search. 1 when `exact` is empty.
double candidate_recall(const std::vector<std::vector<int>>& found, const std::vector<std::vector<int>>& exact);

}  // namespace gmg
