// Parts of a body found by joint name, for any skeleton the readers accept (SMPL-X as BEAT2 ships
// it, ZEGGS/Mixamo, the GENEA 2023 skeleton): legs for foot locking and the foot metrics, wrists
// and the upper body for the speed and beat metrics.
#pragma once

#include <vector>

#include "engine/motion/motion.h"

namespace gmg {

struct Leg {
  int hip = -1, knee = -1, ankle = -1;
  double length = 0.0;  // rest length hip -> knee -> ankle, in file units
};

// The two legs of a skeleton, or none. The topmost joint of a chain whose name holds "ankle" or
// "foot" is the ankle, its parent the knee, its grandparent the hip (SMPL-X left_ankle;
// ZEGGS/Mixamo LeftFoot; GENEA b_l_foot_twist). Anything but exactly two such legs gives none.
std::vector<Leg> find_legs(const Skeleton& skeleton);

// Joint indices of the wrists: names containing "wrist", else names ending in "hand".
std::vector<int> wrist_joints(const Skeleton& skeleton);

// The jaw: the joint named "jaw" (ASCII case-insensitive: SMPL-X's joint 22), else the one joint
// whose name holds "jaw" (a rig's "Jaw", "b_jaw"); -1 when there is none or several. Its local
// rotation opens the mouth.
int jaw_joint(const Skeleton& skeleton);

// The upper body, ascending: every joint on the chains from the root to the wrists and to the
// head (the topmost joint whose name holds "head"), without the root itself. So the spine, neck,
// head, collars, shoulders, elbows and wrists, but no fingers, face or legs: as EMAGE's beat
// alignment takes SMPL-X joints 3, 6, 9, 12-21. Without wrists or a head, every joint but the root
// and the legs' subtrees.
std::vector<int> upper_body_joints(const Skeleton& skeleton);

}  // namespace gmg
