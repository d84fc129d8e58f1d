#include "engine/assemble/transitions.h"

#include <cmath>

#include "engine/assemble/foot_lock.h"
#include "engine/assemble/inertialize.h"
#include "engine/assemble/timeline.h"
#include "engine/core/error.h"
#include "engine/motion/rotation.h"

namespace gmg {
namespace {

// A whole-skeleton pose: local rotations and translations per joint.
struct Pose {
  std::vector<glm::dquat> rot;
  std::vector<glm::dvec3> tr;
};

// Per-joint velocities, per output frame: rotations as exponential-map vectors in the parent's
// frame (q(t) = exp(w) q(t - 1)), translations as vectors.
struct Velocity {
  std::vector<glm::dvec3> ang;
  std::vector<glm::dvec3> lin;
};

// Reads the source at fractional times inside its capture runs, so a velocity never differences
// across a break.
class SourceReader {
 public:
  SourceReader(const Motion& m, const CaptureRuns& runs) : m_(m), runs_(runs) {}

  // Whether time t can be read in the same capture run as frame `from`.
  bool readable(double t, int from) const { return runs_.readable(t, from); }

  void sample(double t, Pose& out) const {
    const int f = static_cast<int>(std::floor(t));
    const double a = t - f;
    const int g = runs_.next_frame(f, a);
    const int joints = m_.joint_count();
    out.rot.resize(static_cast<std::size_t>(joints));
    out.tr.resize(static_cast<std::size_t>(joints));
    for (int j = 0; j < joints; ++j) {
      out.rot[static_cast<std::size_t>(j)] =
          g == f ? m_.rotation(f, j) : slerp_shortest(m_.rotation(f, j), m_.rotation(g, j), a);
      out.tr[static_cast<std::size_t>(j)] = (1.0 - a) * m_.translation(f, j) + a * m_.translation(g, j);
    }
  }

  // The source's own velocity at time t, at `rate` source frames per output frame: backward
  // inside its capture run, forward at the run's start; zero for a held frame (rate 0).
  void velocity(double t, double rate, const Pose& at, Velocity& out) const {
    const int joints = m_.joint_count();
    out.ang.assign(static_cast<std::size_t>(joints), glm::dvec3(0.0));
    out.lin.assign(static_cast<std::size_t>(joints), glm::dvec3(0.0));
    double partner = 0.0, sign = 1.0;
    if (!runs_.velocity_partner(t, rate, partner, sign)) return;
    Pose other;
    sample(partner, other);
    for (int j = 0; j < joints; ++j) {
      const std::size_t k = static_cast<std::size_t>(j);
      out.ang[k] = sign * quat_to_expmap(at.rot[k] * glm::conjugate(other.rot[k]));
      out.lin[k] = sign * (at.tr[k] - other.tr[k]);
    }
  }

 private:
  const Motion& m_;
  const CaptureRuns& runs_;
};

// The decaying offsets of every joint, and the root's horizontal anchor.
struct Offsets {
  std::vector<glm::dvec3> rot, rot_vel, pos, pos_vel;
  glm::dvec3 anchor{0.0};

  explicit Offsets(int joints)
      : rot(static_cast<std::size_t>(joints), glm::dvec3(0.0)), rot_vel(rot), pos(rot), pos_vel(rot) {}

  void decay(double y) {
    for (std::size_t j = 0; j < rot.size(); ++j) {
      spring_decay(rot[j], rot_vel[j], y, 1.0);
      spring_decay(pos[j], pos_vel[j], y, 1.0);
    }
  }

  // Relaxes the anchor toward 0 by `factor`, but never by more than `budget` this frame.
  void relax_anchor(double factor, double budget) {
    glm::dvec3 step = anchor * (1.0 - factor);
    const double length = glm::length(step);
    if (length > budget) step *= budget / length;
    anchor -= step;
  }

  // A transition: the output was heading to `old_pose` moving at `old_vel` (source terms, before
  // the offsets); from now on the source is `dst` moving at `dst_vel`. The new offsets make the
  // output's pose and velocity continuous. `feet_shift` (horizontal) moves the anchor further, the
  // root's offset taking it back as it decays: the hips then shift over the transition while the
  // feet stay where they were.
  void transition(const Pose& old_pose, const Velocity& old_vel, const Pose& dst, const Velocity& dst_vel,
                  bool anchor_root, const glm::dvec3& feet_shift) {
    for (std::size_t j = 0; j < rot.size(); ++j) {
      const glm::dquat out_old = expmap_to_quat(rot[j]) * old_pose.rot[j];
      rot[j] = quat_to_expmap(out_old * glm::conjugate(dst.rot[j]));
      rot_vel[j] = rot_vel[j] + old_vel.ang[j] - dst_vel.ang[j];
      pos[j] = pos[j] + old_pose.tr[j] - dst.tr[j];
      pos_vel[j] = pos_vel[j] + old_vel.lin[j] - dst_vel.lin[j];
    }
    if (anchor_root && !pos.empty()) {
      // The horizontal jump of the root is not decayed quickly: it becomes the slow anchor.
      anchor += glm::dvec3(pos[0].x, 0.0, pos[0].z) + feet_shift;
      pos[0].x = -feet_shift.x;
      pos[0].z = -feet_shift.z;
    }
  }
};

// The mean of `feet`'s positions relative to the root in `pose` (world axes), horizontal.
glm::dvec3 feet_from_root(const Skeleton& s, const Pose& pose, const std::vector<int>& feet) {
  glm::dvec3 sum(0.0);
  for (int foot : feet) {
    glm::dvec3 p(0.0);
    glm::dquat r(1.0, 0.0, 0.0, 0.0);
    for (int j : chain_to(s, foot)) {
      if (j == 0) {
        r = pose.rot[0];
        continue;
      }
      p += r * pose.tr[static_cast<std::size_t>(j)];
      r = r * pose.rot[static_cast<std::size_t>(j)];
    }
    sum += p;
  }
  sum /= static_cast<double>(feet.size());
  return {sum.x, 0.0, sum.z};
}

// Where the old source would have gone one frame after `p` (its last played frame, whose pose
// and velocity were `previous`, `previous_vel`): on along its own capture when it can, else on at
// its last velocity.
void old_source_next(const SourceReader& reader, const SourceClock& p, const Pose& previous,
                     const Velocity& previous_vel, Pose& out_pose, Velocity& out_vel) {
  const int from = static_cast<int>(std::floor(p.time));
  if (p.rate > 0.0 && reader.readable(p.time + p.rate, from)) {
    reader.sample(p.time + p.rate, out_pose);
    reader.velocity(p.time + p.rate, p.rate, out_pose, out_vel);
    return;
  }
  out_pose = previous;
  for (std::size_t j = 0; j < out_pose.rot.size(); ++j) {
    out_pose.rot[j] = expmap_to_quat(previous_vel.ang[j]) * previous.rot[j];
    out_pose.tr[j] = previous.tr[j] + previous_vel.lin[j];
  }
  out_vel = previous_vel;
}

}  // namespace

Motion assemble_inertialized(const Motion& source, const std::vector<char>& continues,
                             const std::vector<PathPiece>& pieces, const BlendParams& params) {
  if (static_cast<int>(continues.size()) != source.frame_count) throw Error("assemble: continues has the wrong size");
  const CaptureRuns runs(continues);
  return assemble_inertialized(source, runs, capture_facts(source, runs), pieces, params);
}

Motion assemble_inertialized(const Motion& source, const CaptureRuns& runs, const CaptureFacts& facts,
                             const std::vector<PathPiece>& pieces, const BlendParams& params,
                             const std::vector<int>& anchor_feet, const BeatAlignment* beats) {
  if (!(params.halflife_s > 0.0)) throw Error("assemble: transition_halflife must be > 0");
  if (runs.frame_count() != source.frame_count) throw Error("assemble: the capture runs do not cover the source");
  if (!facts.known) throw Error("assemble: the source's capture facts are not known");
  const std::vector<SourceClock> clock = source_timeline(pieces, runs, beats);
  const int joints = source.joint_count();
  Motion out = motion_rest(source.skeleton, source.fps, static_cast<int>(clock.size()));
  const SourceReader reader(source, runs);
  const double y = spring_damping(params.halflife_s * source.fps);
  const bool anchor_root = params.root == RootMode::Anchor;
  const double anchor_factor = anchor_root ? std::exp(-std::log(2.0) / (params.root_halflife_s * source.fps)) : 1.0;
  // The pull back never makes the root step further than the capture's own largest step: it
  // spends at most half of what the current source step leaves of it.
  const double anchor_factor_outside =
      anchor_root ? std::exp(-std::log(2.0) / (0.2 * params.root_halflife_s * source.fps)) : 1.0;
  const double root_step_limit = facts.largest_root_step;
  // The capture's standing area: the horizontal extent of its root, widened by a tenth.
  glm::dvec3 area_lo = facts.root_lo, area_hi = facts.root_hi;
  const glm::dvec3 margin = 0.1 * (area_hi - area_lo);
  area_lo -= margin;
  area_hi += margin;

  Offsets off(joints);
  Pose dst, previous, old_pose;
  Velocity dst_vel, previous_vel, old_vel;
  for (std::size_t i = 0; i < clock.size(); ++i) {
    const SourceClock& c = clock[i];
    // A new run reads another stretch of the source: the pages of the stretches read so far go back
    // (a source read in place from a graph file keeps only what is being read resident).
    if (i > 0 && c.run != clock[i - 1].run) motion_release_pages(source);
    reader.sample(c.time, dst);
    if (i > 0) {
      off.decay(y);
      if (anchor_root && c.run == clock[i - 1].run) {  // a transition frame has its own step
        const glm::dvec3 d = dst.tr[0] - previous.tr[0];
        // Outside the capture's standing area the pull back is five times as fast and may spend the
        // whole step budget: many transitions in a row must not walk the speaker off the floor the
        // capture used.
        const glm::dvec3 at = dst.tr[0] + off.anchor;
        const bool outside = at.x < area_lo.x || at.x > area_hi.x || at.z < area_lo.z || at.z > area_hi.z;
        off.relax_anchor(outside ? anchor_factor_outside : anchor_factor,
                         (outside ? 1.0 : 0.5) * std::max(0.0, root_step_limit - std::hypot(d.x, d.z)));
      }
      if (c.run != clock[i - 1].run) {
        // The last played frame's velocity, needed only here: computed at a transition rather than
        // at every frame (its exponential maps were most of the assembly's time).
        reader.velocity(clock[i - 1].time, clock[i - 1].rate, previous, previous_vel);
        old_source_next(reader, clock[i - 1], previous, previous_vel, old_pose, old_vel);
        reader.velocity(c.time, c.rate, dst, dst_vel);
        const glm::dvec3 shift = anchor_root && !anchor_feet.empty()
                                     ? feet_from_root(source.skeleton, old_pose, anchor_feet) -
                                           feet_from_root(source.skeleton, dst, anchor_feet)
                                     : glm::dvec3(0.0);
        off.transition(old_pose, old_vel, dst, dst_vel, anchor_root, shift);
      }
    }
    for (int j = 0; j < joints; ++j) {
      const std::size_t k = static_cast<std::size_t>(j);
      out.rotations[out.index(static_cast<int>(i), j)] = glm::normalize(expmap_to_quat(off.rot[k]) * dst.rot[k]);
      out.translations[out.index(static_cast<int>(i), j)] =
          dst.tr[k] + off.pos[k] + (j == 0 ? off.anchor : glm::dvec3(0.0));
    }
    previous = dst;
  }
  if (params.foot_lock) {
    const std::vector<Leg> legs = find_legs(source.skeleton);
    if (!legs.empty()) foot_lock(out, clock, legs, foot_tracks(source, facts, legs), params.foot_step_s);
  }
  return out;
}

}  // namespace gmg
