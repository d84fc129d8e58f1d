// Graph construction parameters (paper 4.1, section 5; SPEC "Key nodes", "Edges").
//
// Owned by the graph stage: graph_params_validate checks them once, before a build.
#pragma once

#include <string>

#include "engine/core/enum_names.h"

namespace gmg {

// How the candidate transitions of each frame are found (graph/neighbours.h).
enum class NeighbourSearch {
  Auto,         // Exact up to GraphParams::exact_frames frames, Approximate above
  Exact,        // every pair's distance bounded, the exact candidates (time grows as frames^2)
  Approximate,  // a k-d tree with at most ann_checks distance evaluations per frame
};
inline constexpr EnumName<NeighbourSearch> kNeighbourSearchNames[] = {
    {NeighbourSearch::Auto, "auto"}, {NeighbourSearch::Exact, "exact"}, {NeighbourSearch::Approximate, "approximate"}};

struct GraphParams {
  double lambda_pos = 1.0;          // weight of the joint-position term of the pose distance
  double lambda_vel = 1.0;          // weight of the joint-velocity term
  int l_cn = 5;                     // frames after l whose mean distance is l's continuity threshold
  int l_pn = 10;                    // pruning neighbourhood (frames)
  bool exclude_near = true;         // never jump to |r - l| <= l_pn (a stutter); false = paper-literal
  double min_onset_strength = 5.0;  // raw onset envelope value a peak needs (mean per-band dB rise)
  // Capture jumps: a frame whose distance to the next is above break_jump_factor times the
  // clip's median frame-to-frame distance is a break node. 8x the median is far outside the
  // spread of natural motion (speed rarely exceeds 4x its median in conversational gesture)
  // yet catches the teleports of a broken capture.
  double break_jump_factor = 8.0;
  std::string keywords;  // keyword lexicon file; "" = assets/keywords.txt
  // At most this many transitions out of a frame: the nearest of those that pass both prunings
  // among its candidates, the candidates_per_transition * max_transitions nearest frames under
  // its threshold. So edges grow linearly with frames. 0 = no bound (the paper's analysis).
  // With neighbours Auto the bound applies above exact_frames only: a reference up to
  // exact_frames frames gets the paper's exact, unbounded analysis (graph_transition_bound),
  // because the bound changes which transitions survive pruning (measured on the ZEGGS clip:
  // 689 transitions unbounded, 483 with 20, and output jerk 1.09x -> 1.19x the truth's).
  int max_transitions = 20;
  int candidates_per_transition = 4;
  NeighbourSearch neighbours = NeighbourSearch::Auto;
  // Auto: exact and unbounded up to this many frames (8 min at 30 fps), approximate and bounded
  // above (where the unbounded edges grow as frames^2).
  int exact_frames = 15000;
  int ann_checks = 2000;  // Approximate: frames examined per frame at most; 0 = until exact
};

// Throws gmg::Error naming the first key out of range.
void graph_params_validate(const GraphParams& params);

}  // namespace gmg
