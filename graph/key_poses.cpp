#include "graph/key_poses.h"

#include "graph/features.h"

namespace gmg {

Eigen::VectorXd junction_pose(const MotionGraph& g, int f) {
  const bool has_previous = f > 0 && !(g.node(f - 1).kinds & kBreakNode);
  const bool has_next = f + 1 < g.frame_count() && !(g.node(f).kinds & kBreakNode);
  const int first = has_previous ? f - 1 : f;
  const int last = has_previous || has_next ? first + 1 : f;
  const PoseFeatures pf = pose_features(motion_slice(g.motion, first, last + 1));
  const int column = f - first;
  Eigen::VectorXd v(2 * pf.positions.rows());
  v << pf.positions.col(column), pf.velocities.col(column);
  return v;
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
