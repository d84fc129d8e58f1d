// The layered body: the lower body (root, hips, legs) read from one motion, the upper body
// (spine and everything above) from another, joined at the spine (engine/motion/body_layers.h).
//
// The lower layer decides where the body stands and which way it faces; the upper layer decides
// the gesture. Copying the upper layer's local rotations onto the lower layer's pelvis would tilt
// the chest by however much the two layers' pelvises differ (a weight shift leans the pelvis and
// the spine of that capture leans back to keep the chest upright). So the chest keeps the upper
// layer's own posture: the pelvis's difference from the upper layer's pelvis, in the lower
// layer's heading, is taken up by the spine, spread evenly over its joints so no joint kinks.
#pragma once

#include "engine/motion/body_layers.h"
#include "engine/motion/motion.h"

namespace gmg {

// `upper` and `lower`: the same skeleton and frame count, Y-up. Returns the lower layer's joints
// from `lower`, the others from `upper`, the spine turned by `spine_follow` (0..1) of the pelvis
// difference: 1 keeps the upper layer's chest posture exactly, 0 lets it ride on the lower pelvis.
// Without layers (layers.layered() false) returns `upper`.
Motion join_layers(const Motion& upper, const Motion& lower, const BodyLayers& layers, double spine_follow);

// The rotation about +Y (the heading) in q: q = twist * swing with twist about Y.
glm::dquat heading_of(const glm::dquat& q);

}  // namespace gmg
