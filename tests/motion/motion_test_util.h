// Test data shared by the motion module's tests: a small BVH chain and rotation matrices built
// by hand, independent of the code under test.
#pragma once

#include <Eigen/Core>
#include <cmath>

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

}  // namespace gmg::testing
