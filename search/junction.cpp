#include "search/junction.h"

#include <algorithm>

#include "graph/key_poses.h"
#include "graph/reference_facts.h"

namespace gmg {

JunctionCost::JunctionCost(const MotionGraph& g) : g_(g) {
  // The graph's mean transition weight (computed when it was built or loaded). A graph without
  // transitions has no scale of its own; 1 leaves d_pose as it is.
  const double mean = g.indexed ? g.transition_weight : mean_transition_weight(g.graph);
  if (mean > 0.0) normaliser_ = mean;
  if (!g.key_poses.empty()) keys_ = graph_keys(g);
}

JunctionCost::Pose JunctionCost::features(int f) {
  const Eigen::Index dims = junction_pose_dims(g_.motion.skeleton);
  // A key node's pose is in the graph (the same values junction_pose gives, computed when it was
  // built), so ranking the key nodes does not read the motion.
  const auto key = std::lower_bound(keys_.begin(), keys_.end(), f);
  if (key != keys_.end() && *key == f)
    return Pose(g_.key_poses.data() + static_cast<std::size_t>(key - keys_.begin()) * static_cast<std::size_t>(dims),
                dims);
  auto hit = cache_.find(f);
  if (hit == cache_.end()) hit = cache_.emplace(f, junction_pose(g_, f)).first;
  return Pose(hit->second.data(), hit->second.size());
}

double JunctionCost::cost(int c, int s) {
  if (c == s) return 0.0;
  const Pose a = features(c);
  const Pose b = features(s);
  const Eigen::Index d = a.size() / 2;
  const double pose =
      g_.params.lambda_pos * (a.head(d) - b.head(d)).norm() + g_.params.lambda_vel * (a.tail(d) - b.tail(d)).norm();
  return pose / normaliser_;
}

void JunctionCost::costs(int c, const std::vector<int>& frames, std::vector<double>& out) {
  const Pose a = features(c);
  const Eigen::Index d = a.size() / 2;
  if (frames != batch_frames_) {
    batch_frames_ = frames;
    batch_pos_.resize(d, static_cast<Eigen::Index>(frames.size()));
    batch_vel_.resize(d, static_cast<Eigen::Index>(frames.size()));
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const Pose b = features(frames[k]);
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

void JunctionCost::key_costs(int c, std::size_t first, std::size_t stride, std::size_t count,
                             std::vector<double>& out) {
  const Pose a = features(c);
  const Eigen::Index d = a.size() / 2;
  out.resize(count);
  if (count == 0) return;
  // The key poses lie key after key, 2d values each: the positions of keys first, first + stride,
  // ... are the columns of a d x count matrix with an outer stride of 2d x stride, and the
  // velocities another, d values on. A column's norm is summed as in the copied matrix of `costs`.
  using Columns = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
  const double* base = g_.key_poses.data() + first * static_cast<std::size_t>(2 * d);
  const Eigen::OuterStride<> outer(static_cast<Eigen::Index>(stride) * 2 * d);
  const Columns positions(base, d, static_cast<Eigen::Index>(count), outer);
  const Columns velocities(base + d, d, static_cast<Eigen::Index>(count), outer);
  const Eigen::VectorXd pos = (positions.colwise() - a.head(d)).colwise().norm();
  const Eigen::VectorXd vel = (velocities.colwise() - a.tail(d)).colwise().norm();
  for (std::size_t k = 0; k < count; ++k)
    out[k] = keys_[first + k * stride] == c ? 0.0
                                            : (g_.params.lambda_pos * pos(static_cast<Eigen::Index>(k)) +
                                               g_.params.lambda_vel * vel(static_cast<Eigen::Index>(k))) /
                                                  normaliser_;
}

double JunctionCost::largest_joint_gap(int a, int b) {
  const Pose x = features(a);
  const Pose y = features(b);
  double worst = 0.0;
  for (Eigen::Index j = 0; j + 2 < x.size() / 2; j += 3)
    worst = std::max(worst, (x.segment<3>(j) - y.segment<3>(j)).norm());
  return worst;
}

}  // namespace gmg
