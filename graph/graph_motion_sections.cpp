#include "graph/graph_motion_sections.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "engine/core/checksum.h"
#include "graph/graph_check.h"
#include "graph/key_poses.h"

namespace gmg {

void write_key_pose_sums(ArchiveWriter& w, const MotionGraph& g) {
  const std::size_t dims = static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton));
  const std::size_t keys = g.key_poses.empty() ? 0 : g.key_poses.size() / dims;
  std::vector<std::uint64_t> sums(keys);
  std::size_t stretch = 0;  // the first key whose pages have not been given back
  for (std::size_t k = 0; k < keys && w.writes(); ++k) {
    sums[k] = checksum_of(g.key_poses.data() + k * dims, dims * sizeof(double));
    if ((k + 1 - stretch) * dims * sizeof(double) >= (std::size_t{4} << 20) || k + 1 == keys) {
      g.key_poses.release_pages(stretch * dims, (k + 1 - stretch) * dims);  // spilled by a long build
      stretch = k + 1;
    }
  }
  w.pod<std::uint64_t>(g.key_poses.size());
  w.vec(sums);
}

KeyPoseTail read_key_pose_sums(ArchiveReader& r, const std::string& path, const MotionGraph& g) {
  KeyPoseTail t;
  const std::size_t dims = static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton));
  const std::uint64_t n = r.pod<std::uint64_t>();
  if (n != 0 && n != g.keys.size() * dims) r.fail("key poses disagree with key nodes x pose values");
  t.values = static_cast<std::size_t>(n);
  t.checks = std::make_shared<KeyPoseChecks>();
  t.checks->path = path;
  t.checks->sums = r.vec<std::uint64_t>();
  if (t.checks->sums.size() != (n == 0 ? 0 : g.keys.size())) r.fail("key pose checksums disagree with the key nodes");
  return t;
}

void read_key_poses(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g) {
  const auto [poses, n] = r.aligned<double>();
  if (n != 0 && n != g.keys.size() * static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton)))
    r.fail("key poses disagree with key nodes x pose values");
  bool finite = true;
  r.in_place<double>(n,
                     [&](const double* p, std::size_t, std::size_t m) { finite = finite && count_finite(p, m) == m; });
  if (!finite) r.fail("a key pose value is not finite");
  g.key_poses = Samples<double>::view(poses, n, src.owner);
}

void write_key_sketch(ArchiveWriter& w, const KeyPoseSketch& s) {
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(s.axes));
  w.vec(s.basis);
  w.pod(s.scale);
  w.aligned(s.values.data(), s.values.size());
}

void read_key_sketch(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g, bool has_key_poses) {
  KeyPoseSketch& s = g.key_sketch;
  const std::size_t axes = r.pod<std::uint32_t>();
  const std::size_t dims = static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton)), half = dims / 2;
  if (axes > 64 || axes > half) r.fail("implausible key sketch axes");
  if (axes > 0 && !has_key_poses) r.fail("a key sketch without key poses");
  s.axes = static_cast<int>(axes);
  s.basis = r.vec<double>();
  if (s.basis.size() != 2 * axes * dims) r.fail("the key sketch's basis disagrees with its axes x pose values");
  s.scale = r.pod<double>();
  if (!(s.scale >= 0.0 && std::isfinite(s.scale))) r.fail("the key sketch's scale is negative or not finite");
  // Orthonormal rows (within 1e-12), each zero off its part: what makes the bound a bound.
  for (std::size_t i = 0; i < 2 * axes; ++i) {
    const double* row = s.basis.data() + i * dims;
    const bool positions = i < axes;
    for (std::size_t v = 0; v < dims; ++v)
      if (!std::isfinite(row[v]) || (row[v] != 0.0 && (v < half) != positions))
        r.fail("the key sketch's basis is not zero off its part");
    for (std::size_t k = 0; k <= i; ++k) {
      const double* other = s.basis.data() + k * dims;
      double dot = 0.0;
      for (std::size_t v = 0; v < dims; ++v) dot += row[v] * other[v];
      if (!(std::abs(dot - (k == i ? 1.0 : 0.0)) <= 1e-12)) r.fail("the key sketch's basis is not orthonormal");
    }
  }
  const auto [values, n] = r.aligned<double>();
  if (n != g.keys.size() * 2 * axes) r.fail("the key sketch's values disagree with key nodes x axes");
  bool finite = true;
  r.in_place<double>(n,
                     [&](const double* p, std::size_t, std::size_t m) { finite = finite && count_finite(p, m) == m; });
  if (!finite) r.fail("a key sketch value is not finite");
  s.values = Samples<double>::view(values, n, src.owner);
}

void write_motion(ArchiveWriter& w, const Motion& m, const Samples<double>* key_poses) {
  const std::size_t frames = static_cast<std::size_t>(m.frame_count), joints = m.skeleton.joints.size();
  std::vector<std::uint64_t> sums((frames + kMotionBlockFrames - 1) / kMotionBlockFrames);
  std::size_t stretch = 0;  // the first block whose pages have not been given back
  for (std::size_t b = 0; b < sums.size() && w.writes(); ++b) {
    const std::size_t first = b * kMotionBlockFrames, n = std::min<std::size_t>(kMotionBlockFrames, frames - first);
    sums[b] = motion_block_sum(m, first, n);
    if (b + 1 - stretch == kReleaseBlocks || b + 1 == sums.size()) {  // a long build's motion is spilled to a file
      release_motion(m, stretch * kMotionBlockFrames * joints, (first + n) * joints);
      stretch = b + 1;
    }
  }
  w.pod<std::uint32_t>(kMotionBlockFrames);
  w.vec(sums);
  w.stop_summing();
  if (key_poses) w.aligned(*key_poses);
  w.aligned(m.rotations);
  w.aligned(m.translations);
}

void read_motion(ArchiveReader& r, MotionGraph& g, const std::string& path, MotionCheck mode,
                 const std::function<void(std::size_t)>& summed_to, const std::function<Error()>& damaged,
                 KeyPoseTail* key_poses) {
  Motion& m = g.motion;
  const std::uint32_t per = r.pod<std::uint32_t>();
  if (per < 1 || per > (1u << 20)) r.fail("implausible motion block size");
  const std::size_t frames = static_cast<std::size_t>(m.frame_count), joints = m.skeleton.joints.size();
  const std::size_t blocks = (frames + per - 1) / per;
  auto mb = std::make_shared<MotionBlocks>();
  mb->path = path;
  mb->block_frames = static_cast<int>(per);
  mb->sums = r.vec<std::uint64_t>();
  if (mb->sums.size() != blocks) r.fail("motion block checksums disagree with the frame count");
  summed_to(r.stop_summing());
  if (key_poses) {  // format 9: the key poses, each checked now (OnLoad) or when first read (OnUse)
    const auto [poses, n] = r.aligned<double>();
    if (n != key_poses->values) r.fail("key poses disagree with key nodes x pose values");
    r.skip<double>(n);
    g.key_poses = Samples<double>::view(poses, n, r.owner());
    KeyPoseChecks& kc = *key_poses->checks;
    kc.checked.assign(kc.sums.size(), 0);
    if (mode == MotionCheck::OnUse) {
      if (!kc.sums.empty()) g.unchecked_key_poses = key_poses->checks;
    } else {
      const KeyCheck c = check_key_poses(g, kc, 0, kc.sums.size(), true);
      if (c.damaged) throw damaged();
      if (!c.sound) r.fail(key_pose_named(g, c) + " holds a value that is not finite");
    }
  }
  // Sizes are checked before values: the rotations' count, then the translations'.
  const std::size_t expected = frames * joints;
  const auto rotations = r.aligned<glm::dquat>();
  if (rotations.second != expected) r.fail("motion size disagrees with frames x joints");
  r.skip<glm::dquat>(expected);
  const auto translations = r.aligned<glm::dvec3>();
  if (translations.second != expected) r.fail("motion size disagrees with frames x joints");
  r.skip<glm::dvec3>(expected);
  m.rotations = Samples<glm::dquat>::view(rotations.first, expected, r.owner());
  m.translations = Samples<glm::dvec3>::view(translations.first, expected, r.owner());
  mb->checked.assign(blocks, 0);
  const bool computed_from_motion = !g.capture.known || (g.key_poses.empty() && !g.keys.empty());
  if (mode == MotionCheck::OnUse && !computed_from_motion) {
    g.unchecked_motion = std::move(mb);
    return;
  }
  const BlockCheck c = check_motion_blocks(m, *mb, 0, blocks, true);
  if (c.damaged) throw damaged();
  if (!c.sound)
    r.fail("frame " + std::to_string(c.bad_frame) + " holds a value that is not finite or not a unit rotation");
}

}  // namespace gmg
