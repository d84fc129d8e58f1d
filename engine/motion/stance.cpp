#include "engine/motion/stance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/motion/capture_facts.h"

namespace gmg {
namespace {

glm::dquat heading(const glm::dquat& q) {
  const double n = std::hypot(q.w, q.y);
  return n < 1e-12 ? glm::dquat(1.0, 0.0, 0.0, 0.0) : glm::dquat(q.w / n, 0.0, q.y / n, 0.0);
}

// World rotation and position of every joint of one frame.

}  // namespace

Stance stance_facts(const Motion& m, const CaptureRuns& runs, const BodyLayers& layers) {
  Stance out;
  if (!layers.layered() || m.frame_count < 2) return out;
  const std::size_t frames = static_cast<std::size_t>(m.frame_count);
  std::vector<glm::dquat> rot;
  std::vector<glm::dvec3> pos;
  motion_world_pose(m, 0, rot, pos);
  const int hips = layers.hip_branch;
  if (layers.feet.size() != 2) return out;
  const int feet[2] = {layers.feet[0], layers.feet[1]};
  out.leg_length = 0.5 * (glm::length(pos[static_cast<std::size_t>(feet[0])] - pos[static_cast<std::size_t>(hips)]) +
                          glm::length(pos[static_cast<std::size_t>(feet[1])] - pos[static_cast<std::size_t>(hips)]));
  if (!(out.leg_length > 0.0)) return out;
  const double unit = 1.0 / out.leg_length;
  std::vector<int> leg_joints;
  for (const std::vector<int>& leg : layers.legs) leg_joints.insert(leg_joints.end(), leg.begin(), leg.end());

  std::vector<glm::dvec3> foot_pos[2] = {std::vector<glm::dvec3>(frames), std::vector<glm::dvec3>(frames)};
  std::vector<glm::dvec3> hip_pos(frames);
  std::vector<std::vector<glm::dvec3>> rel(frames);  // leg joints relative to the hips, world axes
  std::vector<float> pose(frames * kStanceDims, 0.0f);
  for (std::size_t f = 0; f < frames; ++f) {
    motion_world_pose(m, static_cast<int>(f), rot, pos);
    const glm::dquat hr = rot[static_cast<std::size_t>(hips)];
    const glm::dvec3 hp = pos[static_cast<std::size_t>(hips)];
    const glm::dquat inv_heading = glm::conjugate(heading(hr));
    hip_pos[f] = hp;
    for (int l = 0; l < 2; ++l) {
      foot_pos[l][f] = pos[static_cast<std::size_t>(feet[l])];
      const glm::dvec3 local = inv_heading * (foot_pos[l][f] - hp) * unit;
      for (int d = 0; d < 3; ++d)
        pose[f * kStanceDims + static_cast<std::size_t>(3 * l + d)] = static_cast<float>(local[d]);
    }
    const glm::dvec3 tilt = inv_heading * hr * glm::dvec3(0.0, 1.0, 0.0);
    pose[f * kStanceDims + 7] = static_cast<float>(tilt.x);
    pose[f * kStanceDims + 8] = static_cast<float>(tilt.z);
    rel[f].resize(leg_joints.size());
    for (std::size_t k = 0; k < leg_joints.size(); ++k) rel[f][k] = pos[static_cast<std::size_t>(leg_joints[k])] - hp;
  }
  motion_release_pages(m);
  // The hips' height above the capture run's lowest foot point.
  for (int first = 0; first < m.frame_count;) {
    const int last = runs.last(first);
    double floor = std::numeric_limits<double>::infinity();
    for (int f = first; f <= last; ++f)
      floor = std::min({floor, foot_pos[0][static_cast<std::size_t>(f)].y, foot_pos[1][static_cast<std::size_t>(f)].y});
    for (int f = first; f <= last; ++f)
      pose[static_cast<std::size_t>(f) * kStanceDims + 6] =
          static_cast<float>((hip_pos[static_cast<std::size_t>(f)].y - floor) * unit);
    first = last + 1;
  }
  std::vector<char> contact[2], low;
  for (int l = 0; l < 2; ++l) foot_contacts(foot_pos[l], runs, out.leg_length, m.fps, contact[l], low);
  std::vector<float> place(2 * frames), speed(frames, 0.0f);
  std::vector<std::uint8_t> planted(frames, 0);
  for (std::size_t f = 0; f < frames; ++f) {
    place[2 * f] = static_cast<float>(hip_pos[f].x * unit);
    place[2 * f + 1] = static_cast<float>(hip_pos[f].z * unit);
  }
  for (std::size_t f = 0; f < frames; ++f) {
    // Differences inside the capture run: backward, forward at its first frame.
    const std::size_t g = f > 0 && runs.continues(static_cast<int>(f) - 1)
                              ? f - 1
                              : (f + 1 < frames && runs.continues(static_cast<int>(f)) ? f + 1 : f);
    double fastest = 0.0;
    for (std::size_t k = 0; k < leg_joints.size(); ++k) fastest = std::max(fastest, glm::length(rel[f][k] - rel[g][k]));
    speed[f] = static_cast<float>(fastest * m.fps * unit);
    const glm::dvec3 d = hip_pos[f] - hip_pos[g];
    const double hip_speed = std::hypot(d.x, d.z) * m.fps * unit;
    planted[f] = contact[0][f] && contact[1][f] && hip_speed < kStanceHipSpeed;
  }
  std::vector<float> sorted = speed;
  const auto at = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() * 35 / 100);
  std::nth_element(sorted.begin(), at, sorted.end());
  out.still_speed = *at;
  out.pose = std::move(pose);
  out.place = std::move(place);
  out.speed = std::move(speed);
  out.planted = std::move(planted);
  out.known = true;
  return out;
}

}  // namespace gmg
