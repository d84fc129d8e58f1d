#include "graph/features.h"

#include <algorithm>

#include "engine/core/error.h"

namespace gmg {

PoseFeatures pose_features(const Motion& m) {
  // FK gives frames x 3J; the features are kept transposed so a frame's values are contiguous.
  const Eigen::MatrixXd world = motion_forward_kinematics(m);
  PoseFeatures f;
  f.positions = world.transpose();
  const Eigen::Index dims = f.positions.rows();
  // Root-relative: where the speaker stands is not part of the gesture. (The landed code zeroed
  // the root before subtracting it, so every other joint kept its world position and two frames
  // of the same gesture at different capture spots looked far apart.)
  const Eigen::MatrixXd root = f.positions.topRows(3);
  for (Eigen::Index j = 0; j < dims / 3; ++j) f.positions.middleRows(3 * j, 3) -= root;
  f.velocities.resize(dims, m.frame_count);
  if (m.frame_count >= 2) {
    f.velocities.rightCols(m.frame_count - 1) =
        f.positions.rightCols(m.frame_count - 1) - f.positions.leftCols(m.frame_count - 1);
    f.velocities.col(0) = f.velocities.col(1);
  } else if (m.frame_count == 1) {
    f.velocities.setZero();
  }
  return f;
}

PoseFeatures clip_features(const Motion& m) {
  // A piece starts one frame early so its first velocity is the clip's (v_t = p_t - p_{t-1}).
  constexpr int kPiece = 4096;
  const std::size_t joints = static_cast<std::size_t>(m.joint_count());
  PoseFeatures out;
  out.positions.resize(3 * static_cast<Eigen::Index>(joints), m.frame_count);
  out.velocities.resize(3 * static_cast<Eigen::Index>(joints), m.frame_count);
  for (int first = 0; first < m.frame_count; first += kPiece) {
    const int from = std::max(0, first - 1), to = std::min(m.frame_count, first + kPiece);
    Motion piece = motion_rest(m.skeleton, m.fps, to - from);
    std::copy(m.rotations.begin() + static_cast<std::ptrdiff_t>(from * joints),
              m.rotations.begin() + static_cast<std::ptrdiff_t>(to * joints), piece.rotations.begin());
    std::copy(m.translations.begin() + static_cast<std::ptrdiff_t>(from * joints),
              m.translations.begin() + static_cast<std::ptrdiff_t>(to * joints), piece.translations.begin());
    const PoseFeatures f = pose_features(piece);
    out.positions.middleCols(first, to - first) = f.positions.rightCols(to - first);
    out.velocities.middleCols(first, to - first) = f.velocities.rightCols(to - first);
  }
  return out;
}

double pose_distance(const PoseFeatures& a, int l, const PoseFeatures& b, int r, const GraphParams& params) {
  return params.lambda_pos * (a.positions.col(l) - b.positions.col(r)).norm() +
         params.lambda_vel * (a.velocities.col(l) - b.velocities.col(r)).norm();
}

double pose_distance(const PoseFeatures& f, int l, int r, const GraphParams& params) {
  return pose_distance(f, l, f, r, params);
}

FeatureStore::FeatureStore(int dims, const std::string& spill_folder, std::size_t memory_limit)
    : dims_(dims), spill_(spill_folder, memory_limit) {}

void FeatureStore::add_clip(const PoseFeatures& clip) {
  if (clip.positions.rows() != dims_) throw Error("FeatureStore: a clip with another joint count");
  if (clip.frame_count() < 2) throw Error("FeatureStore: a clip needs at least 2 frames");
  spill_.append(clip.positions.data(), static_cast<std::size_t>(clip.positions.size()) * sizeof(double));
  const std::size_t first = static_cast<std::size_t>(frames_);
  frames_ += clip.frame_count();
  starts_.resize((static_cast<std::size_t>(frames_) + 63) / 64, 0);
  starts_[first >> 6] |= std::uint64_t{1} << (first & 63);
}

void FeatureStore::finish() {
  bytes_ = spill_.finish();
  positions_ = reinterpret_cast<const double*>(bytes_.data);
}

std::unique_ptr<FeatureStore> FeatureStore::of(const PoseFeatures& f) {
  const int n = f.frame_count();
  const Eigen::Index dims = f.positions.rows();
  auto store = std::make_unique<FeatureStore>(static_cast<int>(dims));
  // Clip starts: where the velocity is not the step from the previous frame.
  int start = 0;
  for (int i = 1; i <= n; ++i) {
    const bool step = i < n && f.velocities.col(i) == f.positions.col(i) - f.positions.col(i - 1);
    if (step) continue;
    if (i < n && !(i + 1 < n && f.velocities.col(i) == f.positions.col(i + 1) - f.positions.col(i)))
      throw Error("pose features: the velocity of frame " + std::to_string(i) + " is not a difference of positions");
    PoseFeatures clip;
    clip.positions = f.positions.middleCols(start, i - start);
    clip.velocities = f.velocities.middleCols(start, i - start);
    if (clip.frame_count() < 2 || clip.velocities.col(0) != clip.positions.col(1) - clip.positions.col(0))
      throw Error("pose features: the velocity of frame " + std::to_string(start) +
                  " is not a difference of positions");
    store->add_clip(clip);
    start = i;
  }
  store->finish();
  return store;
}

double FeatureStore::distance(int l, int r, const GraphParams& params) const {
  const Eigen::Map<const Eigen::VectorXd> pl(position(l), dims_), pr(position(r), dims_);
  const auto [al, bl] = velocity_frames(l);
  const auto [ar, br] = velocity_frames(r);
  const Eigen::Map<const Eigen::VectorXd> pal(position(al), dims_), pbl(position(bl), dims_);
  const Eigen::Map<const Eigen::VectorXd> par(position(ar), dims_), pbr(position(br), dims_);
  thread_local Eigen::VectorXd vl, vr;
  vl = pal - pbl;
  vr = par - pbr;
  return params.lambda_pos * (pl - pr).norm() + params.lambda_vel * (vl - vr).norm();
}

void FeatureStore::release() const {
  if (bytes_.file) bytes_.file->release(0, bytes_.file->size());
}

}  // namespace gmg
