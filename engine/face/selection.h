// The reference stretches the face track plays: one candidate per unit of the new speech (engine/
// face/candidates.h), chosen by dynamic programming (Viterbi) to minimise the target costs plus the
// join costs, as concatenative visual speech synthesis chooses its units. Two stretches that follow
// each other in the reference join for free; any other join costs join_weight times (the faces'
// difference where they meet + join_cost), so the track is cut where faces are close.
#pragma once

#include <vector>

#include "engine/face/candidates.h"

namespace gmg {

// Per unit, the index of the candidate chosen (units with no candidate cannot occur: candidates has
// one list per unit, none empty). Deterministic: ties go to the cheaper-ranked candidate.
std::vector<int> select_face_stretches(const ReferenceFace& r,
                                       const std::vector<std::vector<FaceCandidate>>& candidates,
                                       const FaceParams& params);

// The join cost of playing b right after a (0 when b goes on where a ends in the same clip).
double face_join_cost(const ReferenceFace& r, const FaceCandidate& a, const FaceCandidate& b, const FaceParams& params);

}  // namespace gmg
