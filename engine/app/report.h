// The reenactment report (JSON): how each subsequence was matched.
#pragma once

#include <nlohmann/json.hpp>

#include "engine/app/config.h"
#include "engine/app/pipeline.h"
#include "search/planner.h"

namespace gmg {

// frames, fps, duration_s, seed, parameters (every config key), test_events, one entry per
// subsequence (start_frame, target_length, termination, keyword, accepted, continued, retries,
// fallback, failure, cost, path_length, graph_ranges) and totals (subsequences, accepted,
// failures, fallbacks by name). Everything is taken from the plan, so counts always agree with it.
nlohmann::ordered_json reenactment_report(const Plan& plan, const SpeechEvents& events, const Config& config,
                                          double fps);

}  // namespace gmg
