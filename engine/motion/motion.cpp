#include "engine/motion/motion.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace gmg {

const char* channel_name(Channel c) {
  switch (c) {
    case Channel::Xposition:
      return "Xposition";
    case Channel::Yposition:
      return "Yposition";
    case Channel::Zposition:
      return "Zposition";
    case Channel::Xrotation:
      return "Xrotation";
    case Channel::Yrotation:
      return "Yrotation";
    case Channel::Zrotation:
      return "Zrotation";
  }
  return "?";
}

EulerOrder rotation_order_from_channels(const std::vector<Channel>& channels) {
  EulerOrder order{};
  bool used[3] = {false, false, false};
  int n = 0;
  for (Channel c : channels)
    if (!is_position_channel(c) && !used[channel_axis(c)]) {
      order[n++] = channel_axis(c);
      used[channel_axis(c)] = true;
    }
  for (int axis = 0; axis < 3; ++axis)
    if (!used[axis]) order[n++] = axis;
  return order;
}

int Skeleton::channel_count() const {
  int n = 0;
  for (const Joint& j : joints) n += static_cast<int>(j.channels.size());
  return n;
}

int Skeleton::find(const std::string& name) const {
  for (int i = 0; i < joint_count(); ++i)
    if (joints[i].name == name) return i;
  return -1;
}

bool skeletons_match(const Skeleton& a, const Skeleton& b, std::string* why) {
  auto fail = [&](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (a.joint_count() != b.joint_count())
    return fail("joint counts differ (" + std::to_string(a.joint_count()) + " vs " + std::to_string(b.joint_count()) +
                ")");
  for (int i = 0; i < a.joint_count(); ++i) {
    const Joint& ja = a.joints[i];
    const Joint& jb = b.joints[i];
    if (ja.name != jb.name)
      return fail("joint " + std::to_string(i) + " is '" + ja.name + "' in one and '" + jb.name + "' in the other");
    if (ja.parent != jb.parent) return fail("joint '" + ja.name + "' has different parents");
    if (ja.channels != jb.channels) return fail("joint '" + ja.name + "' has different channels");
  }
  return true;
}

Motion motion_rest(const Skeleton& skeleton, double fps, int frame_count) {
  Motion m;
  m.skeleton = skeleton;
  m.fps = fps;
  m.frame_count = frame_count;
  const std::size_t n = static_cast<std::size_t>(frame_count) * skeleton.joints.size();
  m.rotations.assign(n, glm::dquat(1.0, 0.0, 0.0, 0.0));
  m.translations.resize(n);
  for (int f = 0; f < frame_count; ++f)
    for (int j = 0; j < skeleton.joint_count(); ++j) m.translations[m.index(f, j)] = skeleton.joints[j].offset;
  return m;
}

Motion motion_slice(const Motion& m, int from, int to) {
  if (from < 0 || to < from || to > m.frame_count)
    throw Error("motion_slice: range [" + std::to_string(from) + ", " + std::to_string(to) + ") outside 0.." +
                std::to_string(m.frame_count));
  Motion out;
  out.skeleton = m.skeleton;
  out.fps = m.fps;
  out.frame_count = to - from;
  out.rotations.assign(m.rotations.begin() + static_cast<std::ptrdiff_t>(m.index(from, 0)),
                       m.rotations.begin() + static_cast<std::ptrdiff_t>(m.index(to, 0)));
  out.translations.assign(m.translations.begin() + static_cast<std::ptrdiff_t>(m.index(from, 0)),
                          m.translations.begin() + static_cast<std::ptrdiff_t>(m.index(to, 0)));
  if (!m.euler_hints.empty())
    out.euler_hints.assign(m.euler_hints.begin() + static_cast<std::ptrdiff_t>(m.index(from, 0)),
                           m.euler_hints.begin() + static_cast<std::ptrdiff_t>(m.index(to, 0)));
  return out;
}

void motion_copy_frame(const Motion& src, int src_frame, Motion& dst, int dst_frame) {
  const int joints = src.joint_count();
  for (int j = 0; j < joints; ++j) {
    dst.rotations[dst.index(dst_frame, j)] = src.rotation(src_frame, j);
    dst.translations[dst.index(dst_frame, j)] = src.translation(src_frame, j);
  }
}

Eigen::MatrixXd motion_forward_kinematics(const Motion& m) {
  const int joints = m.joint_count();
  Eigen::MatrixXd out(m.frame_count, 3 * joints);
  std::vector<glm::dquat> world_rot(static_cast<std::size_t>(joints));
  std::vector<glm::dvec3> world_pos(static_cast<std::size_t>(joints));
  for (int f = 0; f < m.frame_count; ++f) {
    for (int j = 0; j < joints; ++j) {
      const int parent = m.skeleton.joints[j].parent;
      const glm::dquat& q = m.rotation(f, j);
      const glm::dvec3& t = m.translation(f, j);
      if (parent < 0) {
        world_rot[j] = q;
        world_pos[j] = t;
      } else {
        world_rot[j] = world_rot[parent] * q;
        world_pos[j] = world_pos[parent] + world_rot[parent] * t;
      }
      out(f, 3 * j + 0) = world_pos[j].x;
      out(f, 3 * j + 1) = world_pos[j].y;
      out(f, 3 * j + 2) = world_pos[j].z;
    }
  }
  return out;
}

void motion_check_finite(const Motion& m, const std::string& what) {
  for (std::size_t i = 0; i < m.rotations.size(); ++i) {
    const glm::dquat& q = m.rotations[i];
    const glm::dvec3& t = m.translations[i];
    if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) ||
        !std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z)) {
      const std::size_t joints = m.skeleton.joints.size();
      throw Error(what + ": frame " + std::to_string(i / joints) + ", joint '" + m.skeleton.joints[i % joints].name +
                  "': value is not finite");
    }
  }
}

void motion_world_pose(const Motion& m, int frame, std::vector<glm::dquat>& out_rot, std::vector<glm::dvec3>& out_pos) {
  const int joints = m.joint_count();
  out_rot.resize(static_cast<std::size_t>(joints));
  out_pos.resize(static_cast<std::size_t>(joints));
  for (int j = 0; j < joints; ++j) {
    const std::size_t k = static_cast<std::size_t>(j);
    const int p = m.skeleton.joints[k].parent;
    const glm::dquat q = m.frame_count > 0 ? m.rotation(frame, j) : glm::dquat(1.0, 0.0, 0.0, 0.0);
    const glm::dvec3 t = m.frame_count > 0 ? m.translation(frame, j) : m.skeleton.joints[k].offset;
    if (p < 0) {
      out_rot[k] = q;
      out_pos[k] = t;
    } else {
      out_rot[k] = out_rot[static_cast<std::size_t>(p)] * q;
      out_pos[k] = out_pos[static_cast<std::size_t>(p)] + out_rot[static_cast<std::size_t>(p)] * t;
    }
  }
}

void motion_release_pages(const Motion& m) {
  // A short reference's pages are kept: mapping them again costs more than the memory they hold
  // (every subsequence of a reenactment would fault its stretches in anew).
  if (m.rotations.size() * sizeof(glm::dquat) + m.translations.size() * sizeof(glm::dvec3) < kKeepMotionPagesBelow)
    return;
  release_mapped_pages(m.rotations.data(), m.rotations.size() * sizeof(glm::dquat));
  release_mapped_pages(m.translations.data(), m.translations.size() * sizeof(glm::dvec3));
  release_mapped_pages(m.euler_hints.data(), m.euler_hints.size() * sizeof(glm::dvec3));
}

void motion_release_frames(const Motion& m, int first, int count) {
  const std::size_t j = static_cast<std::size_t>(m.joint_count());
  const std::size_t at = static_cast<std::size_t>(first) * j;
  const std::size_t n = static_cast<std::size_t>(count) * j;
  m.rotations.release_pages(at, std::min(n, m.rotations.size() - std::min(at, m.rotations.size())));
  m.translations.release_pages(at, std::min(n, m.translations.size() - std::min(at, m.translations.size())));
}

}  // namespace gmg
