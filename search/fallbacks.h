// The termination fallbacks (paper A.1.1; SPEC "Fallbacks"): what the planner tries, in order,
// when no beam search accepted a path. Each one used is counted in the report.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "engine/core/enum_names.h"
#include "search/beam_search.h"

namespace gmg {

enum class Fallback : std::uint8_t {
  None,
  KeywordToRhythm,  // 1: keyword termination found nothing; rhythm termination did
  IgnoreStops,      // 2: paths ran through a share of the stopping nodes
  HoldLastFrame,    // 3: the previous result's last frame repeated to the target length
  ContinueMotion,   // 3, natural planner: the previous result's capture plays on instead of freezing
};
inline constexpr EnumName<Fallback> kFallbackNames[] = {{Fallback::None, "none"},
                                                        {Fallback::KeywordToRhythm, "keyword_to_rhythm"},
                                                        {Fallback::IgnoreStops, "ignore_stops"},
                                                        {Fallback::HoldLastFrame, "hold_last_frame"},
                                                        {Fallback::ContinueMotion, "continue_motion"}};
inline const char* fallback_name(Fallback f) { return enum_name(kFallbackNames, f); }

// Fallback 1: the same request ending at any onset or break node instead of its keyword.
BeamRequest fallback_rhythm_request(const BeamRequest& request);

// Fallback 2, round `round` of `rounds`: the request with a share round / (rounds + 1) of the
// key frames `keys` drawn (one rng draw per key, in order) to be ignored as stopping nodes, so
// paths run through them and grow longer.
BeamRequest fallback_ignore_stops_request(const BeamRequest& request, const std::vector<int>& keys, int frame_count,
                                          int round, int rounds, std::mt19937_64& rng);

}  // namespace gmg
