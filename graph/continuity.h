// Continuity analysis (paper 4.1.2; SPEC "Edges"): which frames are close enough to jump between.
#pragma once

#include <functional>
#include <vector>

#include "graph/features.h"
#include "graph/motion_graph.h"
#include "graph/params.h"

namespace gmg {

// theta_l for every frame: the mean d(l, l + k) over k = 1..l_cn inside l's continuous run
// (run_end[l] is the run's last frame). The last frame of a run has no successor; it uses the
// previous (up to) l_cn frames of its run instead, so clip ends can still jump on. A run of one
// frame gets 0 (no transition out of it).
std::vector<double> continuity_thresholds(const PoseFeatures& f, const std::vector<int>& run_end,
                                          const GraphParams& params);

// Called with (frames analysed, frames) as the analysis advances.
using ContinuityProgress = std::function<void(int, int)>;

// The whole analysis over frames with the given run structure: each frame's candidates K_l
// (graph/neighbours.h: the nearest under its threshold, found by params.neighbours), pruning 1
// and pruning 2 (see graph/pruning.h) in left-frame order, then at most params.max_transitions
// of the survivors, the nearest (by weight, then target): the same rule at every length.
// Returns the unnatural edges ordered by (from, to), weighted by d(l, r). With max_transitions 0 this is the paper's
// analysis: every candidate under the threshold, both prunings. Never holds an N x N matrix.
std::vector<Transition> continuity_analysis(const PoseFeatures& f, const std::vector<int>& run_end,
                                            const GraphParams& params, const ContinuityProgress& progress = {});

namespace neighbours {
class PoseSpace;
}
// The same over a pose space built clip by clip (graph/pose_space.h, graph/build.cpp), with every
// frame's threshold already known (continuity_thresholds of each clip).
std::vector<Transition> continuity_analysis(neighbours::PoseSpace&& space, const std::vector<double>& theta,
                                            const GraphParams& params, const ContinuityProgress& progress = {});

}  // namespace gmg
