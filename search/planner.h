// Planning a whole reenactment: one path per test subsequence, with feature-based start
// nodes, continuation, retries and the three fallbacks (paper 4.2.3, A.1; SPEC sections
// "Feature-based initialisation", "Fallbacks", "Randomness").
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "search/params.h"
#include "graph/motion_graph.h"
#include "search/beam_search.h"
#include "search/segmentation.h"

namespace gmg {

enum class Fallback : std::uint8_t {
  None,
  KeywordToRhythm,   // 1: keyword termination found nothing; rhythm termination did
  IgnoreStops,       // 2: paths ran through a share of the stopping nodes
  HoldLastFrame,     // 3: the previous result's last frame repeated to the target length
};
inline constexpr EnumName<Fallback> kFallbackNames[] = {{Fallback::None, "none"},
                                                       {Fallback::KeywordToRhythm, "keyword_to_rhythm"},
                                                       {Fallback::IgnoreStops, "ignore_stops"},
                                                       {Fallback::HoldLastFrame, "hold_last_frame"}};
inline const char* fallback_name(Fallback f) { return enum_name(kFallbackNames, f); }

struct PlannedSegment {
  Subsequence sub;
  std::vector<int> path;        // graph frames of the chosen path (before resampling to sub.length)
  bool accepted = false;        // a beam search accepted a path (possibly after fallback 1 or 2)
  bool failure = false;         // no accepted path and fallbacks off (the path is a held frame)
  Fallback fallback = Fallback::None;
  int retries = 0;              // beam searches beyond the first
  double cost = 0.0;            // cost of the accepted path (0 otherwise)
  bool continued = false;       // the accepted path started from the previous path's successors
};

struct Plan {
  std::vector<PlannedSegment> segments;

  // Counts over the segments.
  int fallback_count(Fallback f) const;
  int fallback_total() const;  // segments that needed any fallback
  int failure_count() const;
};

// Key-node feature (SPEC): lengths of the l_feat subsequences that follow key frame index i in
// `keys` (ascending), with keys past the end taken as keys.back(), so trailing entries are 0.
std::vector<double> key_feature(const std::vector<int>& keys, std::size_t i, int l_feat);

// Deterministic integer in [0, n) from the engine's generator (std distributions are
// implementation-defined; this keeps output byte-identical across standard libraries).
inline std::uint64_t random_below(std::mt19937_64& rng, std::uint64_t n) { return n == 0 ? 0 : rng() % n; }

// Plans every subsequence in order. `test_keys` are the test key frames as segment_speech used
// them (the subsequence starts and the end frame, ascending). rng is the job's one generator.
Plan plan_reenactment(const MotionGraph& g, const std::vector<Subsequence>& subs, const SearchParams& params,
                      std::mt19937_64& rng);

}  // namespace gmg
