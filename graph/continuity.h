// Continuity analysis (paper 4.1.2; SPEC "Edges"): which frames are close enough to jump between.
#pragma once

#include <cstddef>
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

// How many of a frame's pruning-1 survivors, nearest first, the parallel search keeps for pruning
// 2 with `frames` frames: all of them (K_l's bound, candidate_limit) while they fit in 512 MiB
// (524,288 frames, 4.8 h at 30 fps, at the default bound), fewer for longer references, never
// fewer than 16. Pruning 2 drops a survivor only when an edge from the previous l_pn frames already
// makes the same jump, but on dense references it drops many; a frame whose kept survivors run out
// before it is settled is searched again, in the serial pass, which cost a third more searches on
// a seven-minute reference with 16 kept. 0 with no bound (every survivor is kept, in a list). The
// edges do not depend on it.
std::size_t kept_survivors(int frames, const GraphParams& params);

// The whole analysis over frames with the given run structure: each frame's candidates K_l
// (graph/neighbours.h: the nearest under its threshold, found by params.neighbours), pruning 1
// and pruning 2 (see graph/pruning.h) in left-frame order, then at most params.max_transitions
// of the survivors, the nearest (by weight, then target): the same rule at every length.
// Returns the unnatural edges ordered by (from, to), weighted by d(l, r). With max_transitions 0 this is the paper's
// analysis: every candidate under the threshold, both prunings. Never holds an N x N matrix.
// `kept` (0: kept_survivors) sets how many survivors a frame keeps, for tests of the searched-again path.
std::vector<Transition> continuity_analysis(const PoseFeatures& f, const std::vector<int>& run_end,
                                            const GraphParams& params, const ContinuityProgress& progress = {},
                                            std::size_t kept = 0);

namespace neighbours {
class PoseSpace;
}
// The same over a pose space built clip by clip (graph/pose_space.h, graph/build.cpp), with every
// frame's threshold already known (continuity_thresholds of each clip).
std::vector<Transition> continuity_analysis(neighbours::PoseSpace&& space, const std::vector<double>& theta,
                                            const GraphParams& params, const ContinuityProgress& progress = {},
                                            std::size_t kept = 0);

}  // namespace gmg
