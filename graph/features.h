// Pose features and the pose distance d_pose (paper 4.1.2; SPEC "Motion representation").
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "engine/core/spill.h"
#include "engine/motion/motion.h"
#include "graph/params.h"

namespace gmg {

// Per frame, world joint positions minus the root joint's (translation removed), and their
// velocity v_t = p_t - p_{t-1} (v_0 = v_1). Stored one column per frame (3J x frames), so the
// features of a frame are contiguous: every distance reads two columns.
struct PoseFeatures {
  Eigen::MatrixXd positions;   // 3J x frames; rows 3j..3j+2 are joint j; the root's rows are 0
  Eigen::MatrixXd velocities;  // 3J x frames

  int frame_count() const { return static_cast<int>(positions.cols()); }
};

// Features of one clip (velocities restart at its first frame).
PoseFeatures pose_features(const Motion& m);

// The same computed a few thousand frames at a time: pose_features of a whole hour holds several
// copies of it (forward kinematics, its transpose, the velocities). Bit for bit pose_features's.
PoseFeatures clip_features(const Motion& m);

// d(l, r) = lambda_pos * ||p_l - p_r|| + lambda_vel * ||v_l - v_r||: the graph's one pose
// distance, used for thresholds, edge weights and (in search) junction costs.
double pose_distance(const PoseFeatures& f, int l, int r, const GraphParams& params);

// The same between frame l of `a` and frame r of `b` (same joint count).
double pose_distance(const PoseFeatures& a, int l, const PoseFeatures& b, int r, const GraphParams& params);

// The pose features of every frame of a graph, clip after clip, for its distances in double: the
// positions as pose_features gives them, the velocities not kept but taken again from them as
// pose_features takes them (v_f = p_f - p_{f-1}; at a clip's first frame, the next frame's), so
// distance() is pose_distance bit for bit with half the memory. The positions stay in memory up
// to `memory_limit` bytes, then go to a temporary file in `spill_folder` (engine/core/spill.h;
// "" keeps them all in memory).
class FeatureStore {
 public:
  // (An hour of a 55-joint reference is 1.4 GB of positions.)
  explicit FeatureStore(int dims, const std::string& spill_folder = "", std::size_t memory_limit = 0);

  // Appends a clip's features (>= 2 frames, pose_features of the clip: velocities as above).
  void add_clip(const PoseFeatures& clip);
  // After the last clip: the positions are read from here on (mapped when spilled).
  void finish();
  bool spilled() const { return bytes_.file != nullptr; }

  // The features given whole (a graph in memory, tests). Throws gmg::Error when a velocity is
  // neither its position's step from the previous frame nor, at a clip start, the next frame's.
  static std::unique_ptr<FeatureStore> of(const PoseFeatures& f);

  int frame_count() const { return frames_; }
  int dims() const { return dims_; }
  // Whether frame f (0 <= f < frame_count()) starts a clip.
  bool clip_start(int f) const {
    const std::size_t i = static_cast<std::size_t>(f);
    return (starts_[i >> 6] >> (i & 63)) & 1u;
  }
  const double* position(int f) const {
    return positions_ + static_cast<std::size_t>(f) * static_cast<std::size_t>(dims_);
  }
  // The frames whose positions' difference is f's velocity: (f, f - 1), or (f + 1, f) at a clip start.
  std::pair<int, int> velocity_frames(int f) const { return clip_start(f) ? std::pair{f + 1, f} : std::pair{f, f - 1}; }
  // d(l, r) of graph/features.h, bit for bit as pose_distance computes it.
  double distance(int l, int r, const GraphParams& params) const;
  // Gives the pages of spilled positions back (a pass that reads them here and there calls it now
  // and then, so they do not all stay resident); nothing in memory.
  void release() const;

 private:
  int dims_;
  int frames_ = 0;
  // Bit f set when frame f starts a clip (a bit a frame: every distance asks it twice, and a
  // search over clips' starts grew with their count).
  std::vector<std::uint64_t> starts_;
  SpillFile spill_;
  SpillFile::Bytes bytes_;
  const double* positions_ = nullptr;
};

}  // namespace gmg
