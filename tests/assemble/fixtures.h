// Test fixtures shared by the assembly tests: a one-arm skeleton whose hand path is known.
#pragma once

#include <algorithm>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "engine/motion/motion.h"

namespace gmg::testing {

// One joint chain (root + arm + hand): the arm turns about Z by the given angles.
inline Motion arm_motion(const std::vector<double>& angles) {
  Skeleton sk;
  Joint root;
  root.name = "root";
  root.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition,
                   Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  Joint arm;
  arm.name = "arm";
  arm.parent = 0;
  arm.offset = glm::dvec3(0, 10, 0);
  arm.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  Joint hand;
  hand.name = "hand";
  hand.parent = 1;
  hand.offset = glm::dvec3(30, 0, 0);
  hand.channels = arm.channels;
  sk.joints = {root, arm, hand};
  Motion m = motion_rest(sk, 30.0, static_cast<int>(angles.size()));
  for (int f = 0; f < m.frame_count; ++f)
    m.rotations[m.index(f, 1)] = glm::angleAxis(angles[static_cast<std::size_t>(f)], glm::dvec3(0, 0, 1));
  return m;
}

inline double max_step(const Eigen::MatrixXd& p, int from, int to) {
  double worst = 0.0;
  for (int f = std::max(1, from); f < std::min<int>(static_cast<int>(p.rows()), to); ++f)
    worst = std::max(worst, (p.row(f) - p.row(f - 1)).norm());
  return worst;
}

inline std::vector<double> ramp(double from, double step, int n) {
  std::vector<double> out;
  for (int i = 0; i < n; ++i) out.push_back(from + step * i);
  return out;
}

// Hand positions of an arm whose angle follows `angles`.
inline Eigen::MatrixXd hand_path(const std::vector<double>& angles) {
  return motion_forward_kinematics(arm_motion(angles));
}

}  // namespace gmg::testing
