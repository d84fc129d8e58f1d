// Break nodes from capture jumps (paper 4.1.1; SPEC "Break nodes").
#pragma once

#include <vector>

#include "graph/features.h"
#include "graph/params.h"

namespace gmg {

// Frames i whose position distance ||p_i - p_{i+1}|| is above break_jump_factor x the clip's
// median frame-to-frame distance: the capture jumps there. A clip of fewer than 3 frames, or
// a frozen one (median 0), has none. Ascending.
std::vector<int> capture_jump_frames(const PoseFeatures& f, const GraphParams& params);

// The same from the positions alone (3J x frames), e.g. one clip's columns of a longer reference.
std::vector<int> capture_jump_frames(const Eigen::Ref<const Eigen::MatrixXd>& positions, const GraphParams& params);

}  // namespace gmg
