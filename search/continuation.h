// Continuation first (natural planner; SPEC "Junction-aware search", paper 4.2.2 made wider):
// before any beam search, follow the natural continuation of the previous path and take it when a
// matching stop node lies within [continue_min, continue_max] x l_sub. The path is then stretched
// or squeezed onto the target like any accepted path, so the stop node lands on the test's key
// frame and the gesture keeps its rhythm.
#pragma once

#include <vector>

#include "graph/motion_graph.h"
#include "search/beam_search.h"
#include "search/params.h"

namespace gmg {

// The natural path from frame `from` (inclusive) to the stop node (a stop node of `request`,
// beyond `from`) whose length is nearest l_sub within the window; empty when there is none or the
// capture breaks first. Ties go to the shorter path.
std::vector<int> natural_continuation(const MotionGraph& g, int from, const BeamRequest& request,
                                      const SearchParams& params);

// Every natural path from `from` (inclusive) to a stop node of `request` whose length lies within
// [continue_min, continue_max] x l_sub, shortest first; none when the capture breaks first. The
// speech-driven planner weighs each against the beam's paths.
std::vector<std::vector<int>> natural_continuations(const MotionGraph& g, int from, const BeamRequest& request,
                                                    const SearchParams& params);

// The natural path of exactly `length` frames from `from`, or shorter when the capture breaks
// first (the natural planner's last fallback plays on instead of freezing).
std::vector<int> natural_run(const MotionGraph& g, int from, int length);

}  // namespace gmg
