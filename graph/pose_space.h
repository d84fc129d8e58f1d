// The pose space the candidate search (graph/neighbours.h) works in: the pose features in single
// precision and their principal-axis projections, with the error bounds that let a float
// distance decide a candidate only where it cannot be wrong. Internal to graph/.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "graph/features.h"
#include "graph/float_lanes.h"
#include "graph/params.h"

namespace gmg::neighbours {

// The pose features in single precision (centred, so that float rounding stays small against
// the distances) and their projections on the top principal axes of positions and of
// velocities. For an orthonormal projection E, ||E^T x|| <= ||x||, so
//   lambda_pos ||E_p^T (p_l - p_r)|| + lambda_vel ||E_v^T (v_l - v_r)|| <= d(l, r):
// the lower bound the search prunes with. A frame's projections are sixteen floats, rows 0-7 the
// positions' (kp of them used), rows 8-15 the velocities' (zero where unused, which adds exactly
// nothing). Columns are stored in slots, frame order unless set_order() put them in a search
// tree's order (so a leaf's frames are contiguous in memory). Sums run in the fixed orders of
// graph/float_lanes.h, so every float value is the same in every build.
class PoseSpace {
 public:
  PoseSpace(const PoseFeatures& f, const GraphParams& params);

  // Fills the single-precision features with frame order[s] in slot s (frame order when
  // `order` is empty); the projections follow. Call once, before any distance.
  void set_order(const std::vector<int>& order);

  int frames() const { return n_; }
  static constexpr int kProjections = 16;  // rows of projections(): 8 of positions, 8 of velocities
  int position_dims() const { return kp_; }   // the position rows in use (the rest are 0)
  int velocity_dims() const { return kv_; }   // the velocity rows in use, from row 8
  float lambda_pos() const { return lp_; }
  float lambda_vel() const { return lv_; }
  int slot(int frame) const { return slot_.empty() ? frame : slot_[static_cast<std::size_t>(frame)]; }
  const Eigen::MatrixXf& projections() const { return proj_; }  // kProjections x frames, by slot

  double exact(int l, int r) const { return pose_distance(features_, l, r, params_); }
  // d between the frames in slots a and b, in single precision.
  float approx_slots(int a, int b) const {
    const float* x = feat_.col(a).data();
    const float* y = feat_.col(b).data();
    Sixteen sp = Sixteen::zero(), sv = Sixteen::zero();
    for (int j = 0; j < padded_; j += 16) {
      sp.add_square_of_difference(Sixteen::at(x + j), Sixteen::at(y + j));
      sv.add_square_of_difference(Sixteen::at(x + padded_ + j), Sixteen::at(y + padded_ + j));
    }
    alignas(64) float p[16], v[16];
    sp.store(p);
    sv.store(v);
    return lp_ * std::sqrt(sum16(p)) + lv_ * std::sqrt(sum16(v));
  }
  float approx(int l, int r) const { return approx_slots(slot(l), slot(r)); }
  // An upper bound of |approx - exact| for distances up to d.
  float error(float d) const { return 1e-4f * d + abs_error_; }
  // The float admission radius of frame l's threshold theta.
  float radius(double theta) const {
    return theta > 0 ? static_cast<float>(theta) + error(static_cast<float>(theta)) * 1.01f : -1.0f;
  }
  // Whether a float distance d decides "within theta" alone; otherwise exact() does.
  bool within(int l, int r, float d, double theta) const {
    const float t = static_cast<float>(theta);
    if (d > t + error(t)) return false;
    if (d < t - error(t)) return true;
    return exact(l, r) <= theta;
  }
  // Projected lower bound of d between the frames in slots a and b.
  // (Each sum runs over its eight rows in order, as the tree's leaves compute it for sixteen
  // frames at a time.)
  float lower_bound_slots(int a, int b) const {
    const float* x = proj_.col(a).data();
    const float* y = proj_.col(b).data();
    float sp = 0.0f, sv = 0.0f;
    for (int d = 0; d < 8; ++d) sp += (x[d] - y[d]) * (x[d] - y[d]);
    for (int d = 8; d < 16; ++d) sv += (x[d] - y[d]) * (x[d] - y[d]);
    return lp_ * std::sqrt(sp) + lv_ * std::sqrt(sv);
  }

 private:
  // The top principal axes of the columns of x (as columns): as many as hold all but 1e-4 of the
  // variance, at least 2, at most kMaxAxes (and the dimension).
  static Eigen::MatrixXd principal_axes(const Eigen::MatrixXd& x, const Eigen::VectorXd& mean);

  static constexpr Eigen::Index kMaxAxes = 8;
  const PoseFeatures& features_;
  const GraphParams& params_;
  int n_ = 0, dims_ = 0, padded_ = 0, kp_ = 0, kv_ = 0;
  float lp_ = 1, lv_ = 1, abs_error_ = 0;
  Eigen::MatrixXf feat_;  // [positions, padded; velocities, padded] x slots
  Eigen::MatrixXf proj_;  // kProjections x slots
  Eigen::VectorXd mean_p_, mean_v_;
  std::vector<int> slot_;  // frame -> slot; empty = identity
};

}  // namespace gmg::neighbours
