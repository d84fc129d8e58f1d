// The reenactment report (JSON): how each subsequence was matched.
#pragma once

#include <nlohmann/json.hpp>

#include "engine/config/config.h"
#include "engine/pipeline/speech_analysis.h"
#include "search/planner.h"

namespace gmg {

// frames, fps, duration_s, seed, parameters (every config key), test_events, one entry per
// subsequence (start_frame, target_length, termination, keyword, accepted, continued (the path
// starts at the previous path's natural successor), junction_gap_cm (largest root-relative joint
// distance between the frame the output would have continued into and the path's first frame,
// before any blending; 0 when continued), junction_cost, transitions_inside (unnatural edges
// taken inside the path), speech_cost (its speech distance, 1 = unrelated speech), reuse_cost (the
// decayed plays of its most played frame when chosen), retries, fallback, failure, cost,
// path_length, graph_ranges) and totals (subsequences, accepted, failures, fallbacks by name,
// speech_driven, mean_speech_cost). Everything is taken from the plan, so counts always agree with it.
// `length_to_cm` converts the skeleton's length unit to centimetres for the junction gaps.
// `speech_driven` says whether the graph held the reference speech the natural planner matches
// (a note says so when it did not).
nlohmann::ordered_json reenactment_report(const Plan& plan, const SpeechEvents& events, const Config& config,
                                          double fps, double length_to_cm, bool speech_driven = true);

}  // namespace gmg
