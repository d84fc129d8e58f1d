#include "graph/graph_check.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "engine/core/checksum.h"
#include "engine/core/error.h"
#include "graph/graph_archive.h"
#include "graph/key_poses.h"

namespace gmg {

std::uint64_t motion_block_sum(const Motion& m, std::size_t first, std::size_t frames) {
  const std::size_t joints = m.skeleton.joints.size();
  Checksum c;
  c.add(m.rotations.data() + first * joints, frames * joints * sizeof(glm::dquat));
  c.add(m.translations.data() + first * joints, frames * joints * sizeof(glm::dvec3));
  return c.value();
}

void release_motion(const Motion& m, std::size_t from, std::size_t to) {
  auto back_to_page = [](std::size_t value, std::size_t size) {
    return value * size / kGraphAlign * kGraphAlign / size;
  };
  const std::size_t r = back_to_page(from, sizeof(glm::dquat)), t = back_to_page(from, sizeof(glm::dvec3));
  m.rotations.release_pages(r, to - r);
  m.translations.release_pages(t, to - t);
}

BlockCheck check_motion_blocks(const Motion& m, const MotionBlocks& mb, std::size_t b0, std::size_t b1, bool release) {
  const std::size_t frames = static_cast<std::size_t>(m.frame_count), joints = m.skeleton.joints.size();
  const std::size_t per = static_cast<std::size_t>(mb.block_frames);
  // A unit rotation: its squared norm within 1e-6 of 1, which no rotation with an infinite or NaN
  // part has (the comparison with NaN is false). s - s is 0 for a finite sum and NaN for an
  // infinite or NaN one (std::isfinite, a call, would keep the loop scalar). Each block is checked
  // as a whole (a count with no early exit, so the loops vectorise) and searched for its first bad
  // value only when it has one.
  auto unit = [](const glm::dquat& q) { return std::abs(glm::dot(q, q) - 1.0) <= 1e-6; };
  auto finite = [](const glm::dvec3& v) {
    const double s = v.x + v.y + v.z;
    return s - s == 0.0;
  };
  BlockCheck out;
  std::size_t stretch = b0;  // the first block whose pages have not been given back
  for (std::size_t b = b0; b < b1; ++b) {
    const std::size_t first = b * per, n = std::min(per, frames - first);
    const glm::dquat* q = m.rotations.data() + first * joints;
    const glm::dvec3* t = m.translations.data() + first * joints;
    const std::size_t values = n * joints;
    if (motion_block_sum(m, first, n) != mb.sums[b]) {
      out.sound = false;
      out.damaged = true;
      out.first_frame = first;
      out.last_frame = first + n - 1;
      return out;
    }
    std::size_t good = 0;
    for (std::size_t k = 0; k < values; ++k) good += (unit(q[k]) ? 1 : 0) + (finite(t[k]) ? 1 : 0);
    if (good != 2 * values) {
      std::size_t k = 0;
      while (unit(q[k]) && finite(t[k])) ++k;
      out.sound = false;
      out.bad_frame = first + k / joints;
      return out;
    }
    if (release && (b + 1 - stretch == kReleaseBlocks || b + 1 == b1)) {
      release_motion(m, stretch * per * joints, (first + n) * joints);
      stretch = b + 1;
    }
  }
  return out;
}

KeyCheck check_key_poses(const MotionGraph& g, const KeyPoseChecks& kc, std::size_t k0, std::size_t k1, bool release) {
  const std::size_t dims = static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton));
  KeyCheck out;
  std::size_t stretch = k0;  // the first key whose pages have not been given back
  for (std::size_t k = k0; k < k1; ++k) {
    const double* pose = g.key_poses.data() + k * dims;
    if (checksum_of(pose, dims * sizeof(double)) != kc.sums[k] || count_finite(pose, dims) != dims) {
      out.sound = false;
      out.damaged = checksum_of(pose, dims * sizeof(double)) != kc.sums[k];
      out.key = k;
      return out;
    }
    if (release && ((k + 1 - stretch) * dims * sizeof(double) >= (std::size_t{4} << 20) || k + 1 == k1)) {
      g.key_poses.release_pages(stretch * dims, (k + 1 - stretch) * dims);
      stretch = k + 1;
    }
  }
  return out;
}

std::string key_pose_named(const MotionGraph& g, const KeyCheck& c) {
  return "the junction pose of key node " + std::to_string(c.key) + " (frame " + std::to_string(g.keys[c.key]) + ")";
}

void graph_check_key_poses(const MotionGraph& g, std::size_t first, std::size_t last) {
  KeyPoseChecks* kc = g.unchecked_key_poses.get();
  if (!kc || kc->sums.empty() || first >= kc->sums.size() || first > last) return;
  last = std::min(last, kc->sums.size() - 1);
  const std::lock_guard<std::mutex> lock(kc->mutex);
  for (std::size_t k = first; k <= last; ++k) {
    if (kc->checked[k]) continue;
    const KeyCheck c = check_key_poses(g, *kc, k, k + 1, false);
    if (c.damaged) {
      g.check_unchanged();  // a file cut short or rewritten since the load
      throw Error(kc->path + ": graph file is damaged (checksum mismatch in " + key_pose_named(g, c) + ")");
    }
    if (!c.sound)
      throw Error(kc->path + ": damaged graph file: " + key_pose_named(g, c) + " holds a value that is not finite");
    kc->checked[k] = 1;
  }
}

void graph_check_frames(const MotionGraph& g, int first, int last) {
  MotionBlocks* mb = g.unchecked_motion.get();
  if (!mb || g.frame_count() < 1) return;
  const int per = mb->block_frames;
  const int lo = std::clamp(first, 0, g.frame_count() - 1), hi = std::clamp(last, 0, g.frame_count() - 1);
  if (lo > hi) return;
  const std::lock_guard<std::mutex> lock(mb->mutex);
  bool read = false;
  for (std::size_t b = static_cast<std::size_t>(lo / per); b <= static_cast<std::size_t>(hi / per); ++b) {
    if (mb->checked[b]) continue;
    read = true;
    const BlockCheck c = check_motion_blocks(g.motion, *mb, b, b + 1, false);
    if (c.damaged) {
      g.check_unchanged();  // a file cut short or rewritten since the load
      throw Error(mb->path + ": graph file is damaged (checksum mismatch in frames " + std::to_string(c.first_frame) +
                  " to " + std::to_string(c.last_frame) + ")");
    }
    if (!c.sound)
      throw Error(mb->path + ": damaged graph file: frame " + std::to_string(c.bad_frame) +
                  " holds a value that is not finite or not a unit rotation");
    mb->checked[b] = 1;
  }
  // The pages read are given back, all of the motion's: a read maps the page cache's whole large
  // folio around it (2 MB here), more than the block it reads.
  if (read) motion_release_pages(g.motion);
}

}  // namespace gmg
