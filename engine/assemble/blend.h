// Assembling path pieces into one motion (paper 4.2.4; SPEC "Blending").
#pragma once

#include <vector>

#include "engine/assemble/params.h"
#include "engine/motion/motion.h"

namespace gmg {

// Blend weight i of n (i = 0..n-1), rising from near 0 to near 1: linear (i+1)/(n+1) or a
// logistic curve (steepness 10) rescaled to the same end points.
double blend_weight(int i, int n, BlendCurve curve);

// Concatenates pieces (same skeleton), blending every junction over the last L_l =
// min(l_blend, len(left)) frames of the result so far and the first L_r = min(l_blend,
// len(right)) frames of the right piece. The total frame count is the sum of the pieces'.
//  - mode "offset": the excess E = right's first frame - (left's last frame advanced by the
//    mean of the two pieces' boundary velocities) is spread over the window: left frames k get
//    w_k E added, right frames -(1 - w_k) E (rotations: E^w left-multiplied, by SLERP from the
//    identity). With linear weights every step grows by E / (L_l + L_r + 1); E = 0 changes
//    nothing.
//  - mode "crossfade": SPEC's cross-fade of "left, then its last frame held" into "right's first
//    frame held, then right" with weights rising from 0 to 1.
// Rotations always take the short arc; translations blend linearly.
Motion blend_concatenate(const std::vector<Motion>& pieces, const BlendParams& params);

}  // namespace gmg
