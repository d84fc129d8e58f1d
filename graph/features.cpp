#include "graph/features.h"

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

double pose_distance(const PoseFeatures& a, int l, const PoseFeatures& b, int r, const GraphParams& params) {
  return params.lambda_pos * (a.positions.col(l) - b.positions.col(r)).norm() +
         params.lambda_vel * (a.velocities.col(l) - b.velocities.col(r)).norm();
}

double pose_distance(const PoseFeatures& f, int l, int r, const GraphParams& params) {
  return pose_distance(f, l, f, r, params);
}

}  // namespace gmg
