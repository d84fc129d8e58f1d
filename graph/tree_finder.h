// The candidate search (graph/neighbours.h): a k-d tree over the principal-axis projections of the
// pose space (graph/pose_space.h), searched best first. A node's box bounds d from below for every
// frame in it, and so does each frame's projection; the search opens the boxes in order of that
// bound and stops when the nearest unopened one is beyond the frame's radius (exact), or after
// max_checks frames examined (approximate). Internal to graph/: CandidateSearch wraps it.
#pragma once

#include <vector>

#include "engine/core/row_chunks.h"
#include "graph/candidate_gathering.h"
#include "graph/features.h"
#include "graph/neighbours.h"
#include "graph/params.h"
#include "graph/pose_space.h"

namespace gmg::neighbours {

class CandidateTree {
 public:
  // max_checks 0: searched to the end. theta and params must outlive the tree (and the space's
  // feature store).
  CandidateTree(PoseSpace&& space, const std::vector<double>& theta, const GraphParams& params, long max_checks);

  int frames() const { return space_.frames(); }
  // Frames in tree order (slot s holds frame order()[s]).
  const std::vector<int>& order() const { return order_; }
  const PoseSpace& space() const { return space_; }
  // K_l by ascending r, with float distances (neighbours.h).
  void find(int l, CandidateScratch& scratch, std::vector<Candidate>& out) const;
  // K_l of the frames in slots first .. first + count - 1 (out[i] for frame order()[first + i]):
  // kGroup neighbouring frames at a time searched together (find_group). With a budget, the groups
  // are the tree's leaves, whole whatever the run, and each leaf's walk examines at most
  // kLeafWalkChecks * max_checks frames: the budget is the leaf's, and decides what its frames find.
  void find_run(int first, int count, std::vector<CandidateScratch>& scratch,
                std::vector<std::vector<Candidate>>& out) const;

  // Frames per leaf: one block of projections stored dimension by dimension, so that the lower
  // bounds of a leaf's frames are computed as vectors (as many frames at a time as the registers
  // hold), each frame's in the order of PoseSpace::lower_bound_slots.
  static constexpr int kLeaf = 16;
  // Frames the search takes together (find_group): a leaf's worth. For the exact search 4 and 8
  // were slower on a seven-minute reference, 32 and 64 no faster; the budgeted one takes whole
  // leaves.
  static constexpr int kGroup = 16;
  static_assert(kGroup == kLeaf, "the budgeted search walks the tree once for each leaf");

 private:
  struct Node {
    int begin, end;             // slots (tree order); a leaf's begin is a multiple of kLeaf
    int left = -1, right = -1;  // children; -1 for a leaf
  };

  int build(int begin, int end);
  float box_bound(int node, const float* q) const;
  // Lower bound of d between any frame in node `node`'s box and any in node `other`'s: at most
  // box_bound(node, q) for every q in `other`'s box (each gap is at most that of q, and the sums
  // and roots are monotone).
  float box_box_bound(int node, const float* other_lo, const float* other_hi) const;
  // max_checks: frames the walk examines at most (0: to the end).
  void find_group(int first, int count, long max_checks, CandidateScratch* scratch, std::vector<Candidate>* out) const;
  // Which frames of the leaf starting at slot `begin` have a lower bound within `radius`: bit i
  // for frame begin + i (bits past the leaf's own frames are meaningless).
  unsigned leaf_within(int begin, const float* q, float radius) const;
  // Which of kGroup frames can have a member in leaf node `node`: bit i when the lower bound between
  // the leaf's box and frame i is within radii[i]. `q` holds the frames' projections dimension by
  // dimension (q[d * kGroup + i]). The bound is summed as leaf_within sums a frame's, from gaps no
  // larger than the frame's, so it is at most the bound of every frame of the leaf: a frame whose
  // bit is clear has none of the leaf's frames within its radius.
  unsigned leaf_reached(int node, const float* q, const float* radii) const;
  void take(int l, int sl, int sr, double theta, Gathered& g) const;
  void descend(int l, int sl, const float* q, double theta, Gathered& g, CandidateScratch& s) const;

  PoseSpace space_;
  const std::vector<double>& theta_;
  Allowed allowed_;
  std::size_t k_;
  long max_checks_;
  std::vector<int> order_;  // frames in tree order
  std::vector<Node> nodes_;
  std::vector<float> lo_, hi_;  // every node's box, PoseSpace::kProjections floats a node
  RowChunks blocks_;            // a row per leaf: PoseSpace::kProjections rows of kLeaf projections
};

}  // namespace gmg::neighbours
