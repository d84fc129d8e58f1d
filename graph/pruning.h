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
  explicit EdgeIndex(int frames) : targets_(static_cast<std::size_t>(frames)) {}

  // Adds a -> b. The targets of one source must come in ascending order (the survivors of one
  // left frame are sorted), which `any` relies on.
  void add(int a, int b) { targets_[static_cast<std::size_t>(a)].push_back(b); }

  // True when an edge a -> b exists with a in [a_lo, a_hi] and b in [b_lo, b_hi].
  bool any(int a_lo, int a_hi, int b_lo, int b_hi) const;

  // The pruning-2 test of candidate l -> r.
  bool covers(int l, int r, int l_pn) const {
    return any(l - l_pn, l + l_pn, r - l_pn, r + l_pn) || any(r - l_pn, r + l_pn, l - l_pn, l + l_pn);
  }

 private:
  std::vector<std::vector<int>> targets_;
};

}  // namespace gmg
