#include "graph/key_poses.h"

#include <algorithm>

#include <Eigen/QR>

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

KeyPoseSketch key_pose_sketch(const Samples<double>& key_poses, int pose_dims) {
  KeyPoseSketch s;
  const std::size_t dims = static_cast<std::size_t>(std::max(pose_dims, 0));
  const std::size_t keys = dims > 0 ? key_poses.size() / dims : 0;
  if (keys == 0 || dims < 2) return s;
  const Eigen::Index d = static_cast<Eigen::Index>(dims / 2);
  const Eigen::Index axes = std::min<Eigen::Index>(kSketchAxes, d);
  const std::size_t sample = std::min<std::size_t>(keys, 4096);
  auto pose = [&](std::size_t key) {
    return Eigen::Map<const Eigen::VectorXd>(key_poses.data() + key * dims, static_cast<Eigen::Index>(dims));
  };
  Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(2 * axes, 2 * d);
  for (Eigen::Index part = 0; part < 2; ++part) {
    Eigen::MatrixXd x(static_cast<Eigen::Index>(sample), d);
    for (std::size_t i = 0; i < sample; ++i)
      x.row(static_cast<Eigen::Index>(i)) = pose(i * keys / sample).segment(part * d, d).transpose();
    const Eigen::MatrixXd centred = x.rowwise() - x.colwise().mean();
    Eigen::MatrixXd scatter = Eigen::MatrixXd::Zero(d, d);
    scatter.selfadjointView<Eigen::Lower>().rankUpdate(centred.transpose());
    scatter = scatter.selfadjointView<Eigen::Lower>();
    // The axes along which the sample spreads most, by subspace iteration from the values of
    // largest variance: a few products with the scatter matrix, each made orthonormal again. A
    // full eigen-decomposition of the 165 x 165 matrix of a 55-joint body took longer than the
    // rest of a one-minute clip's build; any orthonormal axes keep the sketch a lower bound, and
    // these hold nearly all of the spread.
    std::vector<Eigen::Index> order(static_cast<std::size_t>(d));
    for (Eigen::Index i = 0; i < d; ++i) order[static_cast<std::size_t>(i)] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](Eigen::Index a, Eigen::Index b) { return scatter(a, a) > scatter(b, b); });
    Eigen::MatrixXd v = Eigen::MatrixXd::Zero(d, axes);
    for (Eigen::Index a = 0; a < axes; ++a) v(order[static_cast<std::size_t>(a)], a) = 1.0;
    for (int step = 0; step < 16; ++step) {
      const Eigen::MatrixXd spread = scatter * v;
      v = Eigen::HouseholderQR<Eigen::MatrixXd>(spread).householderQ() * Eigen::MatrixXd::Identity(d, axes);
    }
    basis.block(part * axes, part * d, axes, d) = v.transpose();
  }
  s.axes = static_cast<int>(axes);
  s.basis.resize(static_cast<std::size_t>(basis.size()));
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(s.basis.data(), 2 * axes, 2 * d) =
      basis;
  std::vector<double> values(keys * static_cast<std::size_t>(2 * axes));
  constexpr std::size_t kStretch = 4096;  // keys between giving a long build's spilled poses back
  for (std::size_t k = 0; k < keys; ++k) {
    const auto p = pose(k);
    Eigen::Map<Eigen::VectorXd>(values.data() + k * static_cast<std::size_t>(2 * axes), 2 * axes) = basis * p;
    s.scale = std::max({s.scale, p.head(d).norm(), p.tail(d).norm()});
    if ((k + 1) % kStretch == 0 || k + 1 == keys) {
      const std::size_t first = k / kStretch * kStretch;
      key_poses.release_pages(first * dims, (k + 1 - first) * dims);
    }
  }
  s.values = std::move(values);
  return s;
}

}  // namespace gmg
