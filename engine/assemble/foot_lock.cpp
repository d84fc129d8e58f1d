#include "engine/assemble/foot_lock.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/assemble/inertialize.h"
#include "engine/core/error.h"
#include "engine/motion/rotation.h"

namespace gmg {
namespace {

constexpr double kStepLift = 0.12;  // leg lengths: the highest step (10 cm for a 0.85 m leg)

glm::dquat rotation_between(const glm::dvec3& from, const glm::dvec3& to) {
  const glm::dvec3 a = glm::normalize(from), b = glm::normalize(to);
  const glm::dvec3 axis = glm::cross(a, b);
  const double s = glm::length(axis);
  const double angle = std::atan2(s, glm::dot(a, b));
  if (s < 1e-12) return glm::dquat(1.0, 0.0, 0.0, 0.0);
  return glm::angleAxis(angle, axis / s);
}

// Two-joint IK: moves the leg's ankle (chain's last three joints are hip, knee, ankle) to `target`
// and gives the ankle the world orientation `ankle_world`. Bends the knee in its own plane to the
// reach the target needs, then swings the leg about the hip. The knee turns about `bend`, its
// hinge (knee_hinge).
void leg_ik(Motion& m, int f, const std::vector<int>& chain, const glm::dvec3& target, const glm::dquat& ankle_world,
            const glm::dvec3& bend) {
  std::vector<glm::dquat> wr;
  std::vector<glm::dvec3> wp;
  chain_world(m, f, chain, wr, wp);
  const std::size_t n = chain.size();
  const glm::dvec3 a = wp[n - 3], b = wp[n - 2], c = wp[n - 1];
  const double lab = glm::length(b - a), lcb = glm::length(c - b);
  if (lab < 1e-9 || lcb < 1e-9) return;
  const double lat = std::clamp(glm::length(target - a), std::abs(lab - lcb) + 1e-6, lab + lcb - 1e-6);
  glm::dquat knee_turn(1.0, 0.0, 0.0, 0.0);
  const glm::dvec3 normal = glm::cross(a - b, c - b);
  const glm::dvec3 axis = bend;
  if (glm::length(axis) > 0.0) {
    const double inner = std::acos(std::clamp(glm::dot(glm::normalize(a - b), glm::normalize(c - b)), -1.0, 1.0));
    const double now = glm::dot(normal, axis) >= 0.0 ? inner : 2.0 * 3.14159265358979323846 - inner;
    const double want = std::acos(std::clamp((lab * lab + lcb * lcb - lat * lat) / (2.0 * lab * lcb), -1.0, 1.0));
    knee_turn = glm::angleAxis(want - now, axis);
  }
  const glm::dvec3 c1 = b + knee_turn * (c - b);
  const glm::dquat swing = rotation_between(c1 - a, target - a);
  const glm::dquat hip_world = swing * wr[n - 3];
  const glm::dquat knee_world = swing * knee_turn * wr[n - 2];
  const glm::dquat parent_world = n >= 4 ? wr[n - 4] : glm::dquat(1.0, 0.0, 0.0, 0.0);
  m.rotations[m.index(f, chain[n - 3])] = glm::normalize(glm::conjugate(parent_world) * hip_world);
  m.rotations[m.index(f, chain[n - 2])] = glm::normalize(glm::conjugate(hip_world) * knee_world);
  m.rotations[m.index(f, chain[n - 1])] = glm::normalize(glm::conjugate(knee_world) * ankle_world);
}

// The knee's hinge in world space at frame f: the hinge axis learnt from the capture (in the thigh's
// frame, FootTrack::hinge) turned by the output's thigh. Taken from the pose's own knee plane
// instead, a nearly straight leg has no plane to give: its normal swings and flips with noise, and
// IK about it swung the knee 17-42 cm in one frame. Without a learnt hinge, the pose's plane.
glm::dvec3 knee_hinge(const Motion& m, int f, const std::vector<int>& chain, const glm::dvec3& hinge) {
  std::vector<glm::dquat> wr;
  std::vector<glm::dvec3> wp;
  chain_world(m, f, chain, wr, wp);
  const std::size_t n = chain.size();
  if (glm::length(hinge) > 0.0) return glm::normalize(wr[n - 3] * hinge);
  const glm::dvec3 normal = glm::cross(wp[n - 3] - wp[n - 2], wp[n - 1] - wp[n - 2]);
  return glm::length(normal) > 1e-12 ? glm::normalize(normal) : glm::dvec3(0.0);
}

}  // namespace

FootTrack::FootTrack(const Motion& source, const CaptureFacts& facts, const Leg& leg, int index)
    : source_(&source),
      flags_(facts.foot_flags.data()),
      contact_bit_(foot_contact_bit(index)),
      low_bit_(foot_low_bit(index)),
      chain_(chain_to(source.skeleton, leg.ankle)),
      hinge_(facts.knee_hinges[static_cast<std::size_t>(index)]) {}

void FootTrack::world(int f, glm::dvec3& pos, glm::dquat& rot) const {
  std::vector<glm::dquat> wr;
  std::vector<glm::dvec3> wp;
  chain_world(*source_, f, chain_, wr, wp);
  pos = wp.back();
  rot = wr.back();
}

std::vector<FootTrack> foot_tracks(const Motion& source, const CaptureFacts& facts, const std::vector<Leg>& legs) {
  if (!facts.known || facts.knee_hinges.size() != legs.size() ||
      facts.foot_flags.size() != (legs.empty() ? 0u : static_cast<std::size_t>(source.frame_count)))
    throw Error("assemble: the capture facts do not describe this source's legs");
  std::vector<FootTrack> out;
  for (std::size_t l = 0; l < legs.size(); ++l) out.emplace_back(source, facts, legs[l], static_cast<int>(l));
  return out;
}

namespace {

// The source ankle at a fractional source time (the next frame when the capture continues).
void track_at(const FootTrack& t, double time, glm::dvec3& pos, glm::dquat& rot) {
  const int f = static_cast<int>(std::floor(time));
  const double a = time - static_cast<double>(f);
  const int g = a > 0.0 && f + 1 < t.frame_count() ? f + 1 : f;
  glm::dvec3 pf, pg;
  glm::dquat rf, rg;
  t.world(f, pf, rf);
  if (g == f) {
    pos = (1.0 - a) * pf + a * pf;
    rot = rf;
    return;
  }
  t.world(g, pg, rg);
  pos = (1.0 - a) * pf + a * pg;
  rot = slerp_shortest(rf, rg, a);
}

// Where a foot stepping from (from, from_rot) towards the leg's own foot (foot, foot_rot) is shown
// at s of the step (0 < s <= 1). The step blends with smootherstep (position, velocity and
// acceleration continuous at both ends) and rises on 16 s^2 (1 - s)^2 times `height`, which leads
// the blend: the foot leaves the floor before it moves along it and lands before it stops.
void step_pose(const glm::dvec3& from, const glm::dquat& from_rot, const glm::dvec3& foot, const glm::dquat& foot_rot,
               double height, double s, glm::dvec3& pos, glm::dquat& rot) {
  const double w = s * s * s * (s * (6.0 * s - 15.0) + 10.0);
  pos = (1.0 - w) * from + w * foot + glm::dvec3(0.0, height * 16.0 * s * s * (1 - s) * (1 - s), 0.0);
  rot = slerp_shortest(from_rot, foot_rot, w);
}

}  // namespace

void foot_lock(Motion& out, const std::vector<SourceClock>& clock, const std::vector<Leg>& legs,
               const std::vector<FootTrack>& tracks, double step_s) {
  const int step_frames = std::max(3, static_cast<int>(std::lround(step_s * out.fps)));
  std::vector<glm::dquat> wr;
  std::vector<glm::dvec3> wp;
  for (std::size_t l = 0; l < legs.size(); ++l) {
    const Leg& leg = legs[l];
    const FootTrack& track = tracks[l];
    const std::vector<int> chain = chain_to(out.skeleton, leg.ankle);
    bool locked = false;
    bool held = false;  // locked through a transition, and the new source has not touched down yet
    // While anchored: where the foot is shown, moved each frame by the captured foot's own motion
    // (not across a transition).
    glm::dvec3 anchor(0.0), src_previous(0.0);
    glm::dquat anchor_rot(1.0, 0.0, 0.0, 0.0), src_previous_rot = anchor_rot;
    // A step after a release: from where the foot was (step_pos, step_rot) to where the output's
    // own leg puts it, over step_frames frames; step_at counts them (step_frames: no step).
    glm::dvec3 step_pos(0.0), shown(0.0), foot_before(0.0);
    glm::dquat step_rot = anchor_rot, shown_rot = anchor_rot;
    double step_height = 0.0;
    int step_at = step_frames;
    double settle_from = 0.0;  // height a foot planted mid-step still had, let down over settle_frames
    int settle_frames = 1, settle_at = 1;
    for (int i = 0; i < out.frame_count; ++i) {
      const SourceClock& c = clock[static_cast<std::size_t>(i)];
      chain_world(out, i, chain, wr, wp);
      const glm::dvec3 bend = knee_hinge(out, i, chain, track.hinge());
      const glm::dvec3 hip = wp[wp.size() - 3], foot = wp.back();
      if (i == 0) foot_before = foot;
      const glm::dquat foot_rot = wr.back();
      glm::dvec3 src;
      glm::dquat src_rot;
      track_at(track, c.time, src, src_rot);
      const bool same_run = i > 0 && c.run == clock[static_cast<std::size_t>(i) - 1].run;
      if (i > 0 && !same_run) track.release_source_pages();
      const int sf = static_cast<int>(std::floor(c.time));
      const bool contact = track.contact(sf);
      const bool low = track.low(sf);
      if (locked && !same_run && i > 0) held = !contact;
      if (held && (contact || !low)) held = false;
      if (locked && same_run && !held) {
        anchor += src - src_previous;
        anchor_rot = glm::normalize((src_rot * glm::conjugate(src_previous_rot)) * anchor_rot);
      }
      src_previous = src;
      src_previous_rot = src_rot;
      // Where the foot is shown when free: the leg's own pose, or on its way there in a step.
      glm::dvec3 free_pos = foot;
      glm::dquat free_rot = foot_rot;
      if (step_at < step_frames)
        step_pose(step_pos, step_rot, foot, foot_rot, step_height, static_cast<double>(++step_at) / step_frames,
                  free_pos, free_rot);
      // A foot on its way in a step is planted where it is once the step is past its middle and the
      // source has the foot on the ground (waiting for the step to end left it sliding along the
      // floor, docs/decisions.md Blending; earlier, it would be planted again where it just left),
      // and whatever height it still has it lets down over what is left of the step
      // (planted mid-arc it would stay in the air).
      if (contact && !locked && 2 * step_at >= step_frames) {
        locked = true;
        anchor = free_pos;  // where the foot is shown now
        anchor_rot = free_rot;
        settle_from = step_at < step_frames ? std::max(0.0, free_pos.y - foot.y) : 0.0;
        settle_frames = std::max(1, step_frames - step_at);
        settle_at = 0;
        anchor.y -= settle_from;
        step_at = step_frames;
      }
      double settle = 0.0;
      if (locked && settle_at < settle_frames) {
        const double s = static_cast<double>(++settle_at) / settle_frames;
        settle = settle_from * (1.0 - s * s * s * (s * (6.0 * s - 15.0) + 10.0));
      }
      // An anchor the leg can hardly reach any more (the body moved on) is released too: once it
      // asks the leg to stretch more than 3 % of its length beyond the capture's own pose here (or
      // beyond its full length), before the knee locks straight and the foot is dragged.
      const double reach = std::min(leg.length, glm::length(foot - hip) + 0.03 * leg.length);
      if (locked && ((!contact && !held) || glm::length(anchor - hip) > reach)) {
        locked = false;
        held = false;
        // The foot steps from where it was shown to where the leg now puts it, as high as half the
        // way it has to go (at most kStepLift leg lengths).
        step_pos = shown;
        step_rot = shown_rot;
        // As high as the way is long (the way to the leg's foot now, and as far again as that
        // foot moves in a step's time), up to kStepLift leg lengths at a fifth of a leg's way.
        const double way = std::hypot(foot.x - shown.x, foot.z - shown.z) +
                           std::hypot(foot.x - foot_before.x, foot.z - foot_before.z) * step_frames;
        step_height = kStepLift * leg.length * std::min(1.0, way / (0.2 * leg.length));
        step_at = 0;
        free_pos = shown;
        free_rot = shown_rot;
      }
      foot_before = foot;
      shown = locked ? anchor + glm::dvec3(0.0, settle, 0.0) : free_pos;
      shown_rot = locked ? anchor_rot : free_rot;
      if (locked || step_at < step_frames) leg_ik(out, i, chain, shown, shown_rot, bend);
    }
  }
}

}  // namespace gmg
