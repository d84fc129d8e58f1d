// Test data shared by the motion module's tests: a small BVH chain and rotation matrices built
// by hand, independent of the code under test.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <vector>

#include "engine/motion/motion.h"
#include "engine/motion/npz.h"

namespace gmg::testing {

// A 3-joint chain: root (6 channels, ZXY), mid (3 channels, XYZ), tip (3 channels, YZX).
inline const char* const kChainBvh =
    "HIERARCHY\r\n"
    "ROOT root\r\n{\r\n\tOFFSET 0 0 0\r\n\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\r\n"
    "\tJOINT mid\r\n\t{\r\n\t\tOFFSET 0 1 0\r\n\t\tCHANNELS 3 Xrotation Yrotation Zrotation\r\n"
    "\t\tJOINT tip\r\n\t\t{\r\n\t\t\tOFFSET 0 0 2\r\n\t\t\tCHANNELS 3 Yrotation Zrotation Xrotation\r\n"
    "\t\t\tEnd Site\r\n\t\t\t{\r\n\t\t\t\tOFFSET 1 0 0\r\n\t\t\t}\r\n\t\t}\r\n\t}\r\n}\r\n"
    "MOTION\r\nFrames: 2\r\nFrame Time: 0.0333333\r\n"
    "1 2 3 10 20 30 40 -50 60 70 80 -90\r\n"
    "0 0 0 0 0 0 90 0 0 0 0 0\r\n";

// Rotation matrices built by hand, independent of the code under test.
inline Eigen::Matrix3d axis_matrix(int axis, double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d m;
  if (axis == 0) m << 1, 0, 0, 0, c, -s, 0, s, c;
  if (axis == 1) m << c, 0, s, 0, 1, 0, -s, 0, c;
  if (axis == 2) m << c, -s, 0, s, c, 0, 0, 0, 1;
  return m;
}

// An SMPL-X skeleton in a BVH's depth-first order (not SMPL-X's): the 55 joints with SMPL-X's
// parents, written children-first as a BVH exporter walks them; ROOT OFFSET 0 (BEAT2's BVH).
inline Skeleton smplx_depth_first() {
  const int parents[55] = {-1, 0,  0,  0,  1,  2,  3,  4,  5,  6,  7,  8,  9,  9,  9,  12, 13, 14, 16,
                           17, 18, 19, 15, 15, 15, 20, 25, 26, 20, 28, 29, 20, 31, 32, 20, 34, 35, 20,
                           37, 38, 21, 40, 41, 21, 43, 44, 21, 46, 47, 21, 49, 50, 21, 52, 53};
  Skeleton sk;
  std::vector<int> new_index(55, -1);
  std::function<void(int)> visit = [&](int k) {
    Joint j;
    j.name = smplx_joint_names()[static_cast<std::size_t>(k)];
    j.parent = parents[k] < 0 ? -1 : new_index[static_cast<std::size_t>(parents[k])];
    j.offset = parents[k] < 0 ? glm::dvec3(0.0) : glm::dvec3(0.01 * k, 0.1, 0.0);
    j.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
    if (parents[k] < 0)
      j.channels.insert(j.channels.begin(), {Channel::Xposition, Channel::Yposition, Channel::Zposition});
    j.rotation_order = rotation_order_from_channels(j.channels);
    new_index[static_cast<std::size_t>(k)] = sk.joint_count();
    sk.joints.push_back(j);
    for (int c = 0; c < 55; ++c)
      if (parents[c] == k) visit(c);
  };
  visit(0);
  return sk;
}

}  // namespace gmg::testing
