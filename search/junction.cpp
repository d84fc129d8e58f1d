#include "search/junction.h"

#include <algorithm>
#include <cmath>

#include "graph/graph_check.h"
#include "graph/key_poses.h"
#include "graph/reference_facts.h"

namespace gmg {

JunctionCost::JunctionCost(const MotionGraph& g) : g_(g) {
  // The graph's mean transition weight (computed when it was built or loaded). A graph without
  // transitions has no scale of its own; 1 leaves d_pose as it is.
  const double mean = g.indexed ? g.transition_weight : mean_transition_weight(g);
  if (mean > 0.0) normaliser_ = mean;
  if (!g.key_poses.empty()) keys_ = graph_keys(g);
}

JunctionCost::Pose JunctionCost::features(int f) {
  const Eigen::Index dims = junction_pose_dims(g_.motion.skeleton);
  // A key node's pose is in the graph (the same values junction_pose gives, computed when it was
  // built), so ranking the key nodes does not read the motion.
  const auto key = std::lower_bound(keys_.begin(), keys_.end(), f);
  if (key != keys_.end() && *key == f) {
    const std::size_t k = static_cast<std::size_t>(key - keys_.begin());
    graph_check_key_poses(g_, k, k);  // served from the file: checked when first read
    return Pose(g_.key_poses.data() + k * static_cast<std::size_t>(dims), dims);
  }
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

void JunctionCost::key_lower_bounds(int c, const std::vector<std::size_t>& keys, std::vector<double>& out) {
  out.assign(keys.size(), 0.0);
  const KeyPoseSketch& sketch = g_.key_sketch;
  if (sketch.axes == 0 || keys.empty()) return;
  const Pose a = features(c);
  const Eigen::Index axes = sketch.axes, d = a.size() / 2;
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> basis(
      sketch.basis.data(), 2 * axes, 2 * d);
  const Eigen::VectorXd mine = basis * a;
  // What rounding can add to a sketched distance, against the distance of the poses themselves:
  // each coordinate is a sum of d products (relative error d x 2^-53 of the pose's norm), the basis
  // is orthonormal to 1e-12 (graph_io checks it) and the norms are sums of a few hundred squares.
  // 1e-8 of the norms is far above all of that and far below any distance a ranking tells apart.
  const double slack_pos = 1e-8 * (a.head(d).norm() + sketch.scale);
  const double slack_vel = 1e-8 * (a.tail(d).norm() + sketch.scale);
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const Eigen::Map<const Eigen::VectorXd> theirs(sketch.values.data() + keys[k] * static_cast<std::size_t>(2 * axes),
                                                   2 * axes);
    const double pos = std::max(0.0, (mine.head(axes) - theirs.head(axes)).norm() - slack_pos);
    const double vel = std::max(0.0, (mine.tail(axes) - theirs.tail(axes)).norm() - slack_vel);
    out[k] = (g_.params.lambda_pos * pos + g_.params.lambda_vel * vel) / normaliser_ * (1.0 - 1e-9);
  }
}

void JunctionCost::key_costs(int c, const std::vector<std::size_t>& keys, std::vector<double>& out) {
  const Pose a = features(c);
  const Eigen::Index d = a.size() / 2;
  out.resize(keys.size());
  // The key poses lie key after key, 2d values each: the positions of a run of consecutive keys are
  // the columns of a d x run matrix with an outer stride of 2d, and the velocities another, d
  // values on. A column's norm is summed as in the copied matrix of `costs`, whatever its
  // neighbours.
  using Columns = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
  const Eigen::OuterStride<> outer(2 * d);
  for (std::size_t from = 0; from < keys.size();) {
    std::size_t to = from + 1;
    while (to < keys.size() && keys[to] == keys[to - 1] + 1) ++to;
    const Eigen::Index run = static_cast<Eigen::Index>(to - from);
    graph_check_key_poses(g_, keys[from], keys[to - 1]);
    const double* base = g_.key_poses.data() + keys[from] * static_cast<std::size_t>(2 * d);
    // Up to 64 columns at a time into norms on the stack (a run of a sample's block, or a piece of
    // a longer run): no allocation per run.
    using Norms = Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, 64>;
    for (Eigen::Index at = 0; at < run; at += 64) {
      const Eigen::Index cols = std::min<Eigen::Index>(64, run - at);
      const Columns positions(base + at * 2 * d, d, cols, outer);
      const Columns velocities(base + at * 2 * d + d, d, cols, outer);
      const Norms pos = (positions.colwise() - a.head(d)).colwise().norm();
      const Norms vel = (velocities.colwise() - a.tail(d)).colwise().norm();
      for (Eigen::Index i = 0; i < cols; ++i) {
        const std::size_t k = from + static_cast<std::size_t>(at + i);
        out[k] =
            keys_[keys[k]] == c ? 0.0 : (g_.params.lambda_pos * pos(i) + g_.params.lambda_vel * vel(i)) / normaliser_;
      }
    }
    from = to;
  }
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
