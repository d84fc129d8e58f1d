// The exact candidate search (graph/neighbours.h): tiles of left block x right block, right blocks from the left block
// on, so every pair is bounded once and serves both of its directions. A tile's bound is the distance of the weighted
// projections y = [lambda_pos E_p^T p, lambda_vel E_v^T v], whose square (lambda_pos a)^2 + (lambda_vel b)^2 is below
// d^2 = (lambda_pos a + lambda_vel b)^2: one matrix product and no square root per pair. Pairs within reach then get
// the tighter bound and d. Internal to graph/: make_candidate_finder chooses the search.
#pragma once

#include <memory>
#include <vector>

#include "graph/features.h"
#include "graph/neighbours.h"
#include "graph/params.h"

namespace gmg::neighbours {

// theta, features and params must outlive the finder.
std::unique_ptr<CandidateFinder> make_exact_finder(const PoseFeatures& features, const std::vector<double>& theta,
                                                   const GraphParams& params, int workers);

}  // namespace gmg::neighbours
