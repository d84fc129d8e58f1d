#include "graph/key_poses.h"

#include "graph/features.h"

namespace gmg {

namespace {

// Frame f of `motion` (`frames` frames), kinds(i) the node kinds of its frame i.
template <typename Kinds>
Eigen::VectorXd junction_pose_of(const Motion& motion, int frames, const Kinds& kinds, int f) {
  const bool has_previous = f > 0 && !(kinds(f - 1) & kBreakNode);
  const bool has_next = f + 1 < frames && !(kinds(f) & kBreakNode);
  const int first = has_previous ? f - 1 : f;
  const int last = has_previous || has_next ? first + 1 : f;
  const PoseFeatures pf = pose_features(motion_slice(motion, first, last + 1));
  const int column = f - first;
  Eigen::VectorXd v(2 * pf.positions.rows());
  v << pf.positions.col(column), pf.velocities.col(column);
  return v;
}

}  // namespace

Eigen::VectorXd junction_pose(const MotionGraph& g, int f) {
  return junction_pose_of(
      g.motion, g.frame_count(), [&](int i) { return g.node(i).kinds; }, f);
}

void append_key_junction_poses(const Motion& clip, const std::vector<NodeInfo>& nodes, int offset,
                               std::vector<double>& out) {
  auto kinds = [&](int i) { return nodes[static_cast<std::size_t>(offset + i)].kinds; };
  for (int f = 0; f < clip.frame_count; ++f) {
    if (!kinds(f)) continue;
    const Eigen::VectorXd v = junction_pose_of(clip, clip.frame_count, kinds, f);
    out.insert(out.end(), v.data(), v.data() + v.size());
  }
}

std::vector<double> key_junction_poses(const MotionGraph& g) {
  const std::vector<int> keys = g.key_frames();
  const std::size_t dims = static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton));
  std::vector<double> out(keys.size() * dims);
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const Eigen::VectorXd v = junction_pose(g, keys[k]);
    std::copy(v.data(), v.data() + v.size(), out.begin() + static_cast<std::ptrdiff_t>(k * dims));
  }
  return out;
}

}  // namespace gmg
