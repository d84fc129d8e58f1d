// The approximate candidate search (graph/neighbours.h): a k-d tree over the projections of the
// pose space, searched best first. A node's box gives a lower bound of the distance to every frame
// in it, so the search stops when the nearest unopened box is beyond the frame's radius (exact),
// or after max_checks distance evaluations (approximate).
// Internal to graph/: make_candidate_finder chooses the search.
#pragma once

#include <memory>
#include <vector>

#include "graph/features.h"
#include "graph/neighbours.h"
#include "graph/params.h"

namespace gmg::neighbours {

// theta, features and params must outlive the finder.
std::unique_ptr<CandidateFinder> make_tree_finder(const PoseFeatures& features, const std::vector<double>& theta,
                                                  const GraphParams& params, int workers);

}  // namespace gmg::neighbours
