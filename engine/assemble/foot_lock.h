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

#include <cstdint>
#include <vector>

#include "engine/assemble/timeline.h"
#include "engine/motion/body_parts.h"
#include "engine/motion/capture_facts.h"
#include "engine/motion/motion.h"

namespace gmg {

// One leg's ankle in the source capture: whether it is on the ground at a source frame (from the
// reference's capture facts, engine/motion/capture_facts.h), and its world pose there, computed
// when asked (forward kinematics of the leg's chain), so the assembly reads only the source frames
// it plays.
class FootTrack {
 public:
  FootTrack(const Motion& source, const CaptureFacts& facts, const Leg& leg, int index);

  bool contact(int f) const { return (flags_[static_cast<std::size_t>(f)] & contact_bit_) != 0; }
  bool low(int f) const { return (flags_[static_cast<std::size_t>(f)] & low_bit_) != 0; }
  // World position and orientation of the ankle at frame f.
  void world(int f, glm::dvec3& pos, glm::dquat& rot) const;
  int frame_count() const { return source_->frame_count; }
  // The knee's hinge axis in the thigh's frame (CaptureFacts::knee_hinges), 0 when unknown.
  const glm::dvec3& hinge() const { return hinge_; }
  // Gives back the source's pages read so far (engine/motion/motion.h motion_release_pages).
  void release_source_pages() const { motion_release_pages(*source_); }

 private:
  const Motion* source_;
  const std::uint8_t* flags_;
  std::uint8_t contact_bit_, low_bit_;
  std::vector<int> chain_;
  glm::dvec3 hinge_;
};

// Per leg, the source's ankle track (contact as CaptureFacts defines it). `facts` (known, with
// flags for these legs) and `source` must outlive the tracks.
std::vector<FootTrack> foot_tracks(const Motion& source, const CaptureFacts& facts, const std::vector<Leg>& legs);

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
