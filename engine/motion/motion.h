// Motion data: a skeleton and its per-frame local joint transforms, plus forward kinematics.
//
// Plain data with free functions (motion_*), in the style of Holden's Motion-Matching code.
// Frames are stored frame-major: element (frame f, joint j) is at index f * joint_count + j.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/motion/rotation.h"
#include "engine/motion/samples.h"

namespace gmg {

enum class Channel : std::uint8_t { Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation };

const char* channel_name(Channel c);
inline bool is_position_channel(Channel c) { return c <= Channel::Zposition; }
inline int channel_axis(Channel c) { return static_cast<int>(c) % 3; }

// Rotation order of a channel list: the listed rotation axes (outermost first), then any
// missing axes.
EulerOrder rotation_order_from_channels(const std::vector<Channel>& channels);

struct Joint {
  std::string name;
  int parent = -1;                     // index of the parent joint; -1 only for the root; always < own index
  glm::dvec3 offset{0.0};              // rest translation from the parent, in file units
  std::vector<Channel> channels;       // in file order; 0 to 6 entries, each axis at most once per kind
  EulerOrder rotation_order{2, 0, 1};  // rotation axes outermost first: the listed rotation channels,
                                       // then any missing axes (whose angle is always 0)
  bool has_end_site = false;           // an "End Site" block follows the joint's children
  glm::dvec3 end_site{0.0};            // its offset, meaningful only when has_end_site
};

struct Skeleton {
  std::vector<Joint> joints;  // depth-first file order: joints[0] is the root

  int joint_count() const { return static_cast<int>(joints.size()); }
  int channel_count() const;
  int find(const std::string& name) const;  // -1 when absent
};

// True when both skeletons have the same joint names, hierarchy and channel lists. On false,
// *why (when given) says the first difference. Offsets may differ (bone lengths are not identity).
bool skeletons_match(const Skeleton& a, const Skeleton& b, std::string* why = nullptr);

struct Motion {
  Skeleton skeleton;
  double fps = 30.0;    // frames per second (> 0)
  int frame_count = 0;  // >= 0
  // The samples are owned, or read in place from a graph file (engine/motion/samples.h).
  Samples<glm::dquat> rotations;     // local joint rotations, unit, frame_count * joint_count
  Samples<glm::dvec3> translations;  // local joint translations, frame_count * joint_count:
                                     // the position channels where a joint has them (they
                                     // replace the OFFSET), otherwise the OFFSET
  // Optional: empty, or frame_count * joint_count Euler angles (radians, in each joint's
  // rotation_order) exactly as a BVH file gave them. The writer reproduces them where they
  // still describe the stored rotation, so a read-write round trip keeps a file's own choice
  // of Euler solution (files switch solution branches near gimbal lock). Anything that makes
  // new frames (resampling, blending) leaves it empty.
  Samples<glm::dvec3> euler_hints;

  int joint_count() const { return skeleton.joint_count(); }
  std::size_t index(int frame, int joint) const {
    return static_cast<std::size_t>(frame) * skeleton.joints.size() + static_cast<std::size_t>(joint);
  }
  const glm::dquat& rotation(int frame, int joint) const { return rotations[index(frame, joint)]; }
  const glm::dvec3& translation(int frame, int joint) const { return translations[index(frame, joint)]; }
  double duration() const { return frame_count / fps; }
};

// A motion of frame_count frames in the rest pose (identity rotations, offsets as translations).
Motion motion_rest(const Skeleton& skeleton, double fps, int frame_count);

// Frames [from, to) of m. Requires 0 <= from <= to <= m.frame_count.
Motion motion_slice(const Motion& m, int from, int to);

// Copies frame src_frame of src into frame dst_frame of dst (same skeleton).
void motion_copy_frame(const Motion& src, int src_frame, Motion& dst, int dst_frame);

// World joint positions: a frame_count x (3 * joint_count) matrix, columns x, y, z per joint.
Eigen::MatrixXd motion_forward_kinematics(const Motion& m);

// One frame's world rotations and positions of every joint, into out_rot and out_pos (resized);
// for a motion without frames, the rest pose (identity rotations, the skeleton's offsets).
void motion_world_pose(const Motion& m, int frame, std::vector<glm::dquat>& out_rot, std::vector<glm::dvec3>& out_pos);

// Throws gmg::Error naming `what` when any rotation or translation is not finite.
void motion_check_finite(const Motion& m, const std::string& what);

// Gives back the pages of m's samples where they are read in place from a mapped file (a graph's
// motion, graph/graph_io.h): a reader of scattered frames (a planner's poses, an assembly's pieces)
// calls it when done with a stretch, so that what stays resident is what it reads next, not every
// stretch it ever read (engine/core/files.h release_mapped_pages). Nothing for owned samples, nor
// for a motion under kKeepMotionPagesBelow bytes (rotations and translations): keeping all of a
// short reference costs little, and giving it back made every subsequence of a reenactment map its
// stretches anew (a twentieth of a one-minute reenactment from a one-minute reference).
inline constexpr std::size_t kKeepMotionPagesBelow = std::size_t{64} << 20;
void motion_release_pages(const Motion& m);
// The same for frames [first, first + count) only: a pass over a long motion calls it every
// stretch so that a 19 h reference spilled to disk is never all resident at once.
void motion_release_frames(const Motion& m, int first, int count);

}  // namespace gmg
