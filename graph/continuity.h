// Continuity analysis (paper 4.1.2; SPEC "Edges"): which frames are close enough to jump between.
#pragma once

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

// The whole analysis over frames with the given run structure: candidates d(l, r) <= theta_l
// (r != l + 1, and |r - l| > l_pn unless exclude_near is off), pruning 1 and pruning 2 (see
// graph/pruning.h) in left-frame order. Returns the surviving unnatural edges ordered by
// (from, to), weighted by d(l, r). Distances are computed in blocks with a PCA lower bound,
// never as an N x N matrix.
std::vector<Transition> continuity_analysis(const PoseFeatures& f, const std::vector<int>& run_end,
                                            const GraphParams& params);

}  // namespace gmg
