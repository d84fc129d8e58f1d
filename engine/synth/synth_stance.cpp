// The standing speaker's lower body (see synth.h): where the weight is over time, the hips'
// position that gives each knee its bend, and the legs solved so the feet stay planted.
//
// A standing person keeps the knees a little bent and rests on one leg for a few seconds, then
// on the other or on both: the hips move over the loaded leg, that knee straightens (about 6
// degrees of bend) and the other relaxes (about 17); the pelvis drops on the relaxed side. Given
// the two knee bends and the hips' sideways and forward position, the hips' height and roll are
// solved so that each hip joint is as far from its planted ankle as a leg bent by that angle
// reaches; a two-bone solution then places each knee forward of the line from hip to ankle.
#include <algorithm>

#include "engine/core/error.h"
#include "engine/synth/synth_internal.h"

namespace gmg::synth_internal {
namespace {

// A shift of the weight: from `from` to `to` over [start, start + length].
struct Shift {
  double start, length, from, to;
};

glm::dquat quat_of_axes(const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z) {
  return glm::normalize(glm::quat_cast(glm::dmat3(x, y, z)));
}

// World rotation of a leg bone that points from `from` to `to` (the bone runs along its local
// -Y, as in the skeleton's rest pose) and bends about `hinge` (its local X).
glm::dquat bone_rotation(const glm::dvec3& from, const glm::dvec3& to, const glm::dvec3& hinge) {
  const glm::dvec3 y = glm::normalize(from - to);
  return quat_of_axes(hinge, y, glm::cross(hinge, y));
}

}  // namespace

std::vector<double> weight_curve(double fps, std::size_t frame_count, Rng& rng) {
  const double duration = static_cast<double>(frame_count) / fps;
  // The weight's places: -1 right leg, 0 both, +1 left, each reached 70-100 % of the way.
  int state = rng.below(3);
  double level = (state - 1) * rng.uniform(0.7, 1.0);
  std::vector<Shift> shifts;
  for (double t = rng.uniform(1.0, 4.0); t < duration;) {
    state = (state + 1 + rng.below(2)) % 3;  // somewhere else
    const double to = (state - 1) * rng.uniform(0.7, 1.0);
    const double length = rng.uniform(0.8, 1.4);
    shifts.push_back(Shift{t, length, level, to});
    level = to;
    t += length + rng.uniform(2.5, 6.0);
  }
  std::vector<double> w(frame_count, shifts.empty() ? level : shifts.front().from);
  std::size_t k = 0;
  for (std::size_t f = 0; f < frame_count; ++f) {
    const double t = static_cast<double>(f) / fps;
    while (k < shifts.size() && t >= shifts[k].start + shifts[k].length) ++k;
    if (k == shifts.size()) {
      w[f] = level;
    } else {
      const Shift& s = shifts[k];
      w[f] = s.from + (s.to - s.from) * ramp(t, s.start, s.start + s.length);
    }
  }
  return w;
}

LowerBody lower_body(const Skeleton& sk) {
  LowerBody b;
  b.hips = sk.find("Hips");
  for (int side = 0; side < 2; ++side) {
    const std::string p = side == 0 ? "Left" : "Right";
    LegJoints& leg = b.legs[side];
    leg.upleg = sk.find(p + "UpLeg");
    leg.leg = sk.find(p + "Leg");
    leg.foot = sk.find(p + "Foot");
    const int toe = sk.find(p + "ToeBase");
    if (b.hips < 0 || leg.upleg < 0 || leg.leg < 0 || leg.foot < 0 || toe < 0)
      throw Error("synth: the skeleton has no " + p + " leg (UpLeg, Leg, Foot, ToeBase)");
    const auto offset = [&sk](int j) { return sk.joints[static_cast<std::size_t>(j)].offset; };
    leg.hip_offset = offset(leg.upleg);
    leg.thigh = glm::length(offset(leg.leg));
    leg.shin = glm::length(offset(leg.foot));
    // The ankle where the toe's base touches the floor with the foot flat, a little wider than
    // the hips and turned out by 8 degrees.
    const double s = side == 0 ? 1.0 : -1.0;
    leg.ankle = glm::dvec3(leg.hip_offset.x + 2.0 * s, -offset(toe).y, -1.0);
    leg.foot_world = glm::angleAxis(8.0 * s * kDegToRad, glm::dvec3(0, 1, 0));
  }
  return b;
}

double pose_lower_body(Motion& m, int f, const LowerBody& b, const StancePose& p) {
  // The bend each knee needs: the loaded leg nearly straight, the other relaxed.
  const double load_left = 0.5 * (1.0 + std::clamp(p.weight, -1.0, 1.0));
  const double bend[2] = {17.0 - 11.0 * load_left + p.bend_noise, 17.0 - 11.0 * (1.0 - load_left) + p.bend_noise};
  const glm::dquat yaw = glm::angleAxis(p.yaw_deg * kDegToRad, glm::dvec3(0, 1, 0));
  glm::dvec3 root(p.shift_x, 0.0, p.shift_z);
  double roll = 0;
  // Height and roll: each hip joint at the height where its leg, bent by bend[side], reaches
  // the ankle. The hip joints' sideways places move a little with the roll: a few rounds.
  for (int round = 0; round < 4; ++round) {
    const glm::dquat r = yaw * glm::angleAxis(roll, glm::dvec3(0, 0, 1));
    double want[2];
    for (int side = 0; side < 2; ++side) {
      const LegJoints& leg = b.legs[side];
      const glm::dvec3 hip = root + r * leg.hip_offset;
      const double reach = std::sqrt(leg.thigh * leg.thigh + leg.shin * leg.shin +
                                     2.0 * leg.thigh * leg.shin * std::cos(bend[side] * kDegToRad));
      const double dx = hip.x - leg.ankle.x, dz = hip.z - leg.ankle.z;
      want[side] = leg.ankle.y + std::sqrt(std::max(0.0, reach * reach - dx * dx - dz * dz));
    }
    // The hip joints sit at (+-w, -h) from the root: heights y - h cos(roll) +- w sin(roll).
    const double half_width = 0.5 * (b.legs[0].hip_offset.x - b.legs[1].hip_offset.x);
    const double drop = -0.5 * (b.legs[0].hip_offset.y + b.legs[1].hip_offset.y);
    roll = std::asin(std::clamp((want[0] - want[1]) / (2.0 * half_width), -0.5, 0.5));
    root.y = 0.5 * (want[0] + want[1]) + drop * std::cos(roll);
  }
  const glm::dquat root_q = yaw * glm::angleAxis(roll, glm::dvec3(0, 0, 1));
  m.translations[m.index(f, b.hips)] = root;
  m.rotations[m.index(f, b.hips)] = root_q;

  const glm::dvec3 forward = root_q * glm::dvec3(0, 0, 1);
  for (int side = 0; side < 2; ++side) {
    const LegJoints& leg = b.legs[side];
    const glm::dvec3 hip = root + root_q * leg.hip_offset;
    const glm::dvec3 to_ankle = leg.ankle - hip;
    // Never fully straight (the bend keeps the hinge defined).
    const double reach = std::min(glm::length(to_ankle), (leg.thigh + leg.shin) * std::cos(2.0 * kDegToRad));
    const glm::dvec3 along = glm::normalize(to_ankle);
    const glm::dvec3 ahead = glm::normalize(forward - glm::dot(forward, along) * along);
    // The knee: where the thigh and shin meet, forward of the hip-ankle line.
    const double a = (leg.thigh * leg.thigh - leg.shin * leg.shin + reach * reach) / (2.0 * reach);
    const double h = std::sqrt(std::max(0.0, leg.thigh * leg.thigh - a * a));
    const glm::dvec3 knee = hip + a * along + h * ahead;
    const glm::dvec3 ankle = hip + reach * along;
    const glm::dvec3 hinge = glm::normalize(glm::cross(ahead, along));
    const glm::dquat thigh_q = bone_rotation(hip, knee, hinge);
    const glm::dquat shin_q = bone_rotation(knee, ankle, hinge);
    m.rotations[m.index(f, leg.upleg)] = glm::normalize(glm::inverse(root_q) * thigh_q);
    m.rotations[m.index(f, leg.leg)] = glm::normalize(glm::inverse(thigh_q) * shin_q);
    m.rotations[m.index(f, leg.foot)] = glm::normalize(glm::inverse(shin_q) * leg.foot_world);
  }
  return roll / kDegToRad;
}

}  // namespace gmg::synth_internal
