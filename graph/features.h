// Pose features and the pose distance d_pose (paper 4.1.2; SPEC "Motion representation").
#pragma once

#include <Eigen/Core>

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

// d(l, r) = lambda_pos * ||p_l - p_r|| + lambda_vel * ||v_l - v_r||: the graph's one pose
// distance, used for thresholds, edge weights and (in search) junction costs.
double pose_distance(const PoseFeatures& f, int l, int r, const GraphParams& params);

// The same between frame l of `a` and frame r of `b` (same joint count).
double pose_distance(const PoseFeatures& a, int l, const PoseFeatures& b, int r, const GraphParams& params);

}  // namespace gmg
