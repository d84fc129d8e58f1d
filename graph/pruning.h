// The two prunings of candidate transitions (paper 4.1.2; SPEC "Edges").
#pragma once

#include <vector>

#include "graph/neighbours.h"

namespace gmg {

// Pruning 1: candidates of one left frame (right frames, ascending); in each run of consecutive
// frame numbers keep the first, drop the next l_pn - 1, then keep again. l_pn >= 1.
std::vector<int> prune_runs(const std::vector<int>& candidates, int l_pn);
// The same on candidates with their distances (sorted by frame), appended to `out`.
void prune_runs(const std::vector<Candidate>& candidates, int l_pn, std::vector<Candidate>& out);

// Pruning 2: the unnatural edges added so far, by source frame. A candidate l -> r is dropped
// when an edge a -> b exists with |a - l| <= l_pn and |b - r| <= l_pn, or |a - r| <= l_pn and
// |b - l| <= l_pn (the same transition, or its reverse, already nearby).
class EdgeIndex {
 public:
  explicit EdgeIndex(int frames) : frames_(frames) {}

  // Adds a -> b. Sources come in ascending order, and one source's targets too (the analysis adds
  // each frame's survivors, sorted, after the frames before it): the edges are then one array by
  // source, read in place by `any`. Throws gmg::Error for a source out of range or before the last.
  void add(int a, int b);

  // True when an edge a -> b exists with a in [a_lo, a_hi] and b in [b_lo, b_hi].
  bool any(int a_lo, int a_hi, int b_lo, int b_hi) const;

  // The pruning-2 test of candidate l -> r.
  bool covers(int l, int r, int l_pn) const {
    return any(l - l_pn, l + l_pn, r - l_pn, r + l_pn) || any(r - l_pn, r + l_pn, l - l_pn, l + l_pn);
  }

 private:
  int frames_;
  // Source a's targets are targets_[first_[a]] up to the next source's first (or the end, for the
  // last source added); sources past the last added have none. (One array instead of a list per
  // frame: the test reads the 2 l_pn + 1 sources around a far frame r, side by side in memory.)
  std::vector<std::size_t> first_;
  std::vector<int> targets_;
};

}  // namespace gmg
