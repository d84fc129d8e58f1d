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
// Legs are found by name (engine/motion/body_parts.h); without exactly two legs nothing is locked.
#pragma once

#include <vector>

#include "engine/assemble/timeline.h"
#include "engine/motion/body_parts.h"
#include "engine/motion/motion.h"

namespace gmg {

// One leg's ankle in the source capture, per source frame.
struct FootTrack {
  std::vector<char> contact;    // on the ground (see foot_tracks)
  std::vector<char> low;        // near the ground: the height half of the contact test alone
  std::vector<glm::dvec3> pos;  // world position
  std::vector<glm::dquat> rot;  // world orientation
  // The knee's hinge axis in the thigh's frame, learnt from the frames where the capture bends the
  // knee clearly; 0 when it never does (the IK then bends in the pose's own plane).
  glm::dvec3 hinge{0.0};
};

// Per leg, the source's ankle track. A foot is in contact when its world speed is below 0.15 leg
// lengths per second (13 cm/s for a 0.9 m leg: a planted foot's capture noise stays far below, a
// step is ten times faster) and it is within 0.1 leg lengths of the lowest point it reaches in
// its capture run. Runs and gaps shorter than 3 frames are smoothed away.
std::vector<FootTrack> foot_tracks(const Motion& source, const std::vector<char>& continues,
                                   const std::vector<Leg>& legs);

// Anchors the output's feet where the source (read at `clock`) is in contact. A released foot
// steps, over step_s seconds, from where it was to where the output's leg puts it: it rises first
// and lands at rest, as high as half the way it has to go (at most 0.12 leg lengths), instead of
// gliding there along the floor. A foot planted when a transition comes stays planted
// while the new source's foot is still near the ground, even where it moves there: blending a
// planted foot toward a foot that shuffles along the floor would drag it (the commonest slide
// of reassembled motion). It is released once the new source lifts the foot (the offset then
// decays in the air) or the leg cannot reach it; once the new source's foot is in contact
// again, the anchor follows its small moves as usual. `out` is modified in place (hip, knee and ankle rotations).
void foot_lock(Motion& out, const std::vector<SourceClock>& clock, const std::vector<Leg>& legs,
               const std::vector<FootTrack>& tracks, double step_s);

}  // namespace gmg
