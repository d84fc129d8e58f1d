// The body's two layers: a lower body (root, hips, legs) that stands and shifts weight, and an
// upper body (spine, arms, head, hands, face) that gestures with the speech. A reenactment plays
// each from its own path through the reference (search/lower_body.h plans the lower one) and joins
// them at the spine (engine/assemble/layers.h).
//
// The layers are found from the skeleton's geometry, not its joint names, so any rig the readers
// accept splits the same way: in the first frame of the (Y-up) reference, the two lowest end
// joints whose chains from the root part at the hips are the feet; the joint where their chains
// part is the hip branch; every joint from the root to the hip branch and the two leg subtrees
// below it are the lower body; the chain from the hip branch up to the first joint that branches
// again (the chest, where neck and collars part) is the spine; everything else is the upper body.
#pragma once

#include <string>
#include <vector>

#include "engine/motion/motion.h"

namespace gmg {

struct BodyLayers {
  // Per joint: true when the lower layer drives it (the root, the chain to the hip branch, the
  // legs). Empty when the skeleton has no two legs (an upper-body rig): then nothing is layered.
  std::vector<char> lower;
  std::vector<int> legs[2];  // each leg's joints, from the hip down to its foot end
  std::vector<int> feet;     // each leg's foot end: its lowest joint in the first frame
  std::vector<int> spine;    // from the hip branch's upper child up to the chest, ascending
  int hip_branch = -1;       // where the legs part (SMPL-X pelvis, Mixamo Hips, GENEA b_root)

  bool layered() const { return !lower.empty(); }
};

// The layers of `m`'s skeleton from its first frame, which must be in Y-up (engine/motion/up_axis.h
// makes any reference so). A hip branch below a third of the body's height, or legs that do not
// reach the lowest tenth of it, are not legs: the layers are then empty.
BodyLayers find_body_layers(const Motion& m);

// The same with the lower joints named (`names`, every other joint upper): `--set lower_joints=`
// overrides the geometry. Throws gmg::Error naming a joint the skeleton lacks. The legs and spine
// are still found from the geometry where they lie inside / outside `names`.
BodyLayers body_layers_from_names(const Motion& m, const std::vector<std::string>& names);

// "lower: pelvis left_hip ...; spine: spine1 spine2 spine3" for reports and `gmg inspect`.
std::string describe_body_layers(const Skeleton& s, const BodyLayers& layers);

}  // namespace gmg
