#include "search/junction.h"

#include <algorithm>

#include "graph/key_poses.h"

namespace gmg {

JunctionCost::JunctionCost(const MotionGraph& g) : g_(g) {
  double sum = 0.0;
  long count = 0;
  for (auto [it, end] = boost::edges(g.graph); it != end; ++it)
    if (!g.graph[*it].natural) {
      sum += g.graph[*it].weight;
      ++count;
    }
  // A graph without transitions has no scale of its own; 1 leaves d_pose as it is.
  if (count > 0 && sum > 0.0) normaliser_ = sum / static_cast<double>(count);
  if (!g.key_poses.empty()) keys_ = g.key_frames();
}

const Eigen::VectorXd& JunctionCost::features(int f) {
  const auto hit = cache_.find(f);
  if (hit != cache_.end()) return hit->second;
  // A key node's pose is in the graph (the same values junction_pose gives, computed when it was
  // built), so ranking the key nodes does not read the motion.
  const auto key = std::lower_bound(keys_.begin(), keys_.end(), f);
  if (key != keys_.end() && *key == f) {
    const Eigen::Index dims = junction_pose_dims(g_.motion.skeleton);
    const double* p =
        g_.key_poses.data() + static_cast<std::size_t>(key - keys_.begin()) * static_cast<std::size_t>(dims);
    return cache_.emplace(f, Eigen::Map<const Eigen::VectorXd>(p, dims)).first->second;
  }
  return cache_.emplace(f, junction_pose(g_, f)).first->second;
}

double JunctionCost::cost(int c, int s) {
  if (c == s) return 0.0;
  const Eigen::VectorXd& a = features(c);
  const Eigen::VectorXd& b = features(s);
  const Eigen::Index d = a.size() / 2;
  const double pose =
      g_.params.lambda_pos * (a.head(d) - b.head(d)).norm() + g_.params.lambda_vel * (a.tail(d) - b.tail(d)).norm();
  return pose / normaliser_;
}

void JunctionCost::costs(int c, const std::vector<int>& frames, std::vector<double>& out) {
  const Eigen::VectorXd& a = features(c);
  const Eigen::Index d = a.size() / 2;
  if (frames != batch_frames_) {
    batch_frames_ = frames;
    batch_pos_.resize(d, static_cast<Eigen::Index>(frames.size()));
    batch_vel_.resize(d, static_cast<Eigen::Index>(frames.size()));
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const Eigen::VectorXd& b = features(frames[k]);
      batch_pos_.col(static_cast<Eigen::Index>(k)) = b.head(d);
      batch_vel_.col(static_cast<Eigen::Index>(k)) = b.tail(d);
    }
  }
  const Eigen::VectorXd pos = (batch_pos_.colwise() - a.head(d)).colwise().norm();
  const Eigen::VectorXd vel = (batch_vel_.colwise() - a.tail(d)).colwise().norm();
  out.resize(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k)
    out[k] = frames[k] == c ? 0.0
                            : (g_.params.lambda_pos * pos(static_cast<Eigen::Index>(k)) +
                               g_.params.lambda_vel * vel(static_cast<Eigen::Index>(k))) /
                                  normaliser_;
}

double JunctionCost::largest_joint_gap(int a, int b) {
  const Eigen::VectorXd& x = features(a);
  const Eigen::VectorXd& y = features(b);
  double worst = 0.0;
  for (Eigen::Index j = 0; j + 2 < x.size() / 2; j += 3)
    worst = std::max(worst, (x.segment<3>(j) - y.segment<3>(j)).norm());
  return worst;
}

}  // namespace gmg
