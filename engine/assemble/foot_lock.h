// Planted feet stay planted (no foot sliding).
//
// Reassembled motion changes the leg pose at every transition; inertialization carries the old
// pose over and lets it decay, which is smooth but moves a foot that the capture had on the
// ground: it glides. So wherever the source capture has a foot in contact with the ground, the
// output's foot is anchored where it was when the contact began and from there moves only as the
// captured foot moves (its small shifts and capture noise included, nothing from transitions),
// position and orientation; a two-joint IK on hip and knee (the analytic solution of Holden's
// motion matching code) puts it there. When the source lifts the foot, the anchor is released and
// the difference decays like a transition's.
//
// Legs are found by name: the topmost joint of a chain whose name holds "ankle" or "foot" is the
// effector, its parent the knee, its grandparent the hip (SMPL-X left_ankle; ZEGGS/Mixamo LeftFoot;
// GENEA b_l_foot_twist). Without exactly two such legs nothing is locked.
#pragma once

#include <vector>

#include "engine/assemble/timeline.h"
#include "engine/motion/motion.h"

namespace gmg {

struct Leg {
  int hip = -1, knee = -1, ankle = -1;
  double length = 0.0;  // rest length hip -> knee -> ankle, in file units
};

// The two legs of a skeleton, or none (see above).
std::vector<Leg> find_legs(const Skeleton& skeleton);

// One leg's ankle in the source capture, per source frame.
struct FootTrack {
  std::vector<char> contact;    // on the ground (see foot_tracks)
  std::vector<glm::dvec3> pos;  // world position
  std::vector<glm::dquat> rot;  // world orientation
};

// Per leg, the source's ankle track. A foot is in contact when its world speed is below 0.15 leg
// lengths per second (13 cm/s for a 0.9 m leg: a planted foot's capture noise stays far below, a
// step is ten times faster) and it is within 0.1 leg lengths of the lowest point it reaches in
// its capture run. Runs and gaps shorter than 3 frames are smoothed away.
std::vector<FootTrack> foot_tracks(const Motion& source, const std::vector<char>& continues,
                                   const std::vector<Leg>& legs);

// Anchors the output's feet where the source (read at `clock`) is in contact; releases decay with
// the spring of half-life `halflife_s`. `out` is modified in place (hip, knee and ankle rotations).
void foot_lock(Motion& out, const std::vector<SourceClock>& clock, const std::vector<Leg>& legs,
               const std::vector<FootTrack>& tracks, double halflife_s);

}  // namespace gmg
