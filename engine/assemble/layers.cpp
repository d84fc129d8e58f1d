#include "engine/assemble/layers.h"

#include <cmath>
#include <vector>

#include "engine/core/error.h"
#include "engine/motion/rotation.h"

namespace gmg {
namespace {

// World rotation of joint j in frame f (the product of the chain's local rotations).
glm::dquat world_rotation(const Motion& m, int f, int j) {
  glm::dquat q(1.0, 0.0, 0.0, 0.0);
  for (int k = j; k >= 0; k = m.skeleton.joints[static_cast<std::size_t>(k)].parent) q = m.rotation(f, k) * q;
  return q;
}

// q^t along the shorter arc from the identity.
glm::dquat power(const glm::dquat& q, double t) { return slerp_shortest(glm::dquat(1.0, 0.0, 0.0, 0.0), q, t); }

double yaw_of(const glm::dquat& q) {
  const glm::dquat h = heading_of(q);
  return 2.0 * std::atan2(h.y, h.w);
}

// Per frame, the angle about Y from the upper layer's pelvis heading to the lower layer's,
// unwrapped, then smoothed by a Gaussian of kHeadingSigmaS: the chest turns with the legs' heading
// over a second or so, not with every sway of the hips (a standing speaker's hips turn a few degrees
// back and forth with each weight shift while the chest keeps facing the listener).
constexpr double kHeadingSigmaS = 0.5;
std::vector<double> facing_turn(const Motion& upper, const Motion& lower, int hips) {
  const int n = upper.frame_count;
  std::vector<double> raw(static_cast<std::size_t>(n));
  double previous = 0.0;
  for (int f = 0; f < n; ++f) {
    double a = yaw_of(world_rotation(lower, f, hips)) - yaw_of(world_rotation(upper, f, hips));
    if (f > 0) a = previous + std::remainder(a - previous, 2.0 * M_PI);
    raw[static_cast<std::size_t>(f)] = previous = a;
  }
  const double sigma = kHeadingSigmaS * upper.fps;
  const int half = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<double> kernel(static_cast<std::size_t>(2 * half + 1));
  for (int k = -half; k <= half; ++k)
    kernel[static_cast<std::size_t>(k + half)] = std::exp(-0.5 * k * k / (sigma * sigma));
  std::vector<double> out(raw.size());
  for (int f = 0; f < n; ++f) {
    double sum = 0.0, weight = 0.0;
    for (int k = -half; k <= half; ++k) {
      const int g = std::clamp(f + k, 0, n - 1);
      sum += kernel[static_cast<std::size_t>(k + half)] * raw[static_cast<std::size_t>(g)];
      weight += kernel[static_cast<std::size_t>(k + half)];
    }
    out[static_cast<std::size_t>(f)] = sum / weight;
  }
  return out;
}

}  // namespace

glm::dquat heading_of(const glm::dquat& q) {
  const double n = std::hypot(q.w, q.y);
  if (n < 1e-12) return glm::dquat(1.0, 0.0, 0.0, 0.0);  // a half turn about a horizontal axis: no heading
  return glm::dquat(q.w / n, 0.0, q.y / n, 0.0);
}

Motion join_layers(const Motion& upper, const Motion& lower, const BodyLayers& layers, double spine_follow) {
  if (!layers.layered()) return upper;
  if (upper.frame_count != lower.frame_count || upper.joint_count() != lower.joint_count())
    throw Error("join layers: the upper and lower motions differ in frames or joints");
  Motion out = upper;
  out.euler_hints = {};
  const int joints = out.joint_count();
  const bool spine = !layers.spine.empty() && spine_follow > 0.0;
  const std::vector<double> turn = spine ? facing_turn(upper, lower, layers.hip_branch) : std::vector<double>{};
  for (int f = 0; f < out.frame_count; ++f) {
    for (int j = 0; j < joints; ++j)
      if (layers.lower[static_cast<std::size_t>(j)]) {
        out.rotations[out.index(f, j)] = lower.rotation(f, j);
        out.translations[out.index(f, j)] = lower.translation(f, j);
      }
    if (!spine) continue;
    // The pelvis difference in the hip branch's frame, from the lower layer's pelvis to the upper
    // layer's turned to face (smoothly) where the lower one faces. The first spine joint takes all
    // of it, so the whole torso above moves as the upper layer's: spread over the spine, each
    // segment would carry the difference of two unrelated sways (jerk of the neck and head 1.5-1.6 x
    // the reference's against 1.0-1.2 x, BEAT2 new speech).
    const glm::dquat pl = world_rotation(lower, f, layers.hip_branch);
    const glm::dquat pu = world_rotation(upper, f, layers.hip_branch);
    const double a = turn[static_cast<std::size_t>(f)];
    const glm::dquat face(std::cos(0.5 * a), 0.0, std::sin(0.5 * a), 0.0);
    const glm::dquat d = glm::normalize(glm::conjugate(pl) * face * pu);
    const int j = layers.spine.front();
    out.rotations[out.index(f, j)] = glm::normalize(power(d, spine_follow) * upper.rotation(f, j));
  }
  return out;
}

}  // namespace gmg
