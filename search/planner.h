// Planning a whole reenactment: one path per test subsequence (paper 4.2, A.1; SPEC "Beam
// search", "Randomness"). Composes the steps: start nodes (search/start_ranking.h over
// search/initialisation.h), the beam search (search/beam_search.h), continuation from the previous
// path, retries and the three fallbacks (search/fallbacks.h).
#pragma once

#include <random>
#include <vector>

#include "graph/motion_graph.h"
#include "search/anchors.h"
#include "search/beam_search.h"
#include "search/fallbacks.h"
#include "search/params.h"
#include "search/segmentation.h"

namespace gmg {

struct PlannedSegment {
  Subsequence sub;
  std::vector<int> path;  // graph frames of the chosen path (before resampling to sub.length)
  bool accepted = false;  // a beam search accepted a path (possibly after fallback 1 or 2)
  bool failure = false;   // no accepted path and fallbacks off (the path is a held frame)
  Fallback fallback = Fallback::None;
  int retries = 0;         // beam searches beyond the first
  double cost = 0.0;       // cost of the accepted path (0 otherwise)
  bool continued = false;  // the path starts at the previous path's natural successor: no junction
  // The frame the output would have continued into (the previous path's natural successor, or its
  // last frame at a break); -1 for the first subsequence.
  int junction_from = -1;
  double junction_cost = 0.0;  // J(junction_from, path.front()) (search/junction.h); 0 when continued
  double junction_gap = 0.0;   // largest root-relative joint distance of that junction (file units)
  int transitions_inside = 0;  // unnatural edges taken inside the path
  double speech_cost = 0.0;    // speech distance of the path played onto the subsequence (search/speech_match.h)
  double reuse_cost = 0.0;     // reuse cost of its frames when it was chosen (search/reuse.h)
};

struct Plan {
  std::vector<PlannedSegment> segments;

  // Counts over the segments.
  int fallback_count(Fallback f) const;
  int fallback_total() const;  // segments that needed any fallback
  int failure_count() const;
};

// Plans every subsequence in order; rng is the job's one generator. The params are validated
// first. Always ends, with one path per subsequence. `test_speech` holds the test speech features
// (total frames x g.speech_dims, audio/speech_features.h) for the speech-driven costs of the
// natural planner; empty (or a graph without speech features) plans without them.
// `anchors` (search/anchors.h: rests and pins; sorted, not overlapping) are placed among the
// subsequences after the natural planner's merge, and the planner plans around them.
Plan plan_reenactment(const MotionGraph& g, const std::vector<Subsequence>& subs, const SearchParams& params,
                      std::mt19937_64& rng, const std::vector<float>& test_speech = {},
                      const std::vector<Anchor>& anchors = {});

}  // namespace gmg
