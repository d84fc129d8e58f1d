// Rotation conversions: BVH Euler angles <-> unit quaternion <-> exponential map.
//
// Conventions (the BVH ones, used everywhere in the engine):
// - A rotation maps a vector from the joint's frame to its parent's frame: v_parent = q * v_local.
// - BVH channels "Zrotation Xrotation Yrotation" mean q = Rz(a) * Rx(b) * Ry(c): rotations are
//   intrinsic, applied in the order listed, so the first listed axis is the outermost factor.
// - Angles in BVH files are degrees; these functions take and return radians.
// - Quaternions are glm::dquat (w, x, y, z), kept unit length.
#pragma once

#include <array>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace gmg {

// Axis indices 0 = X, 1 = Y, 2 = Z, in channel order (outermost first). All three distinct.
using EulerOrder = std::array<int, 3>;

// "ZXY" -> {2, 0, 1}. Throws gmg::Error when the text is not a permutation of X, Y, Z.
EulerOrder euler_order_from_string(const std::string& text);
std::string euler_order_to_string(const EulerOrder& order);

// angles[i] is the angle about axis order[i] (radians).
glm::dquat euler_to_quat(const glm::dvec3& angles, const EulerOrder& order);

// The Euler angles of q in the given order, with the middle angle in [-pi/2, pi/2].
glm::dvec3 quat_to_euler(const glm::dquat& q, const EulerOrder& order);

// Like quat_to_euler, but of the two equivalent solutions returns the one nearest `previous`
// (angular distance). Angles are in (-pi, pi]. Used when writing BVH so that a joint does not
// flip between the two solution branches from frame to frame.
glm::dvec3 quat_to_euler_near(const glm::dquat& q, const EulerOrder& order, const glm::dvec3& previous);

// The Euler solution of q (of the two, with 2*pi shifts per angle) nearest `reference`. Used to
// write back angles read from a file exactly as the file had them.
glm::dvec3 quat_to_euler_matching(const glm::dquat& q, const EulerOrder& order, const glm::dvec3& reference);

// Exponential map (axis * angle, radians) <-> quaternion. quat_to_expmap returns the angle in [0, pi].
glm::dquat expmap_to_quat(const glm::dvec3& v);
glm::dvec3 quat_to_expmap(const glm::dquat& q);

// Spherical interpolation along the shorter arc (q and -q are the same rotation), t in [0, 1].
glm::dquat slerp_shortest(const glm::dquat& a, const glm::dquat& b, double t);

// The angle of a unit quaternion's rotation, radians in [0, pi] (from atan2, exact for the small
// angles of a jaw, where acos of the real part loses digits).
double rotation_angle(const glm::dquat& q);

// Angle (radians, in [0, pi]) of the rotation taking a to b.
double rotation_angle_between(const glm::dquat& a, const glm::dquat& b);

}  // namespace gmg
