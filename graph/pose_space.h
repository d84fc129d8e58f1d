// The pose space the candidate search (graph/neighbours.h) works in: the pose features in single
// precision and their principal-axis projections, with the error bounds that let a float
// distance decide a candidate only where it cannot be wrong. Internal to graph/.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "graph/features.h"
#include "graph/params.h"

namespace gmg::neighbours {

// The pose features in single precision (centred, so that float rounding stays small against
// the distances) and their projections on the top principal axes of positions and of
// velocities. For an orthonormal projection E, ||E^T x|| <= ||x||, so
//   lambda_pos ||E_p^T (p_l - p_r)|| + lambda_vel ||E_v^T (v_l - v_r)|| <= d(l, r):
// the lower bound both searches prune with. Columns are stored in slots, frame order unless
// set_order() put them in a search tree's order (so a leaf's frames are contiguous in memory).
class PoseSpace {
 public:
  PoseSpace(const PoseFeatures& f, const GraphParams& params);

  // Fills the single-precision features with frame order[s] in slot s (frame order when
  // `order` is empty); the projections follow. Call once, before any distance.
  void set_order(const std::vector<int>& order);

  int frames() const { return n_; }
  int dims() const { return static_cast<int>(proj_.rows()); }
  int position_dims() const { return kp_; }
  float lambda_pos() const { return lp_; }
  float lambda_vel() const { return lv_; }
  int slot(int frame) const { return slot_.empty() ? frame : slot_[static_cast<std::size_t>(frame)]; }
  const Eigen::MatrixXf& projections() const { return proj_; }  // dims x frames, by slot

  double exact(int l, int r) const { return pose_distance(features_, l, r, params_); }
  // d between the frames in slots a and b, in single precision.
  float approx_slots(int a, int b) const {
    const auto x = feat_.col(a), y = feat_.col(b);
    return lp_ * (x.head(padded_) - y.head(padded_)).norm() + lv_ * (x.tail(padded_) - y.tail(padded_)).norm();
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
  float lower_bound_slots(int a, int b) const {
    const float* x = proj_.col(a).data();
    const float* y = proj_.col(b).data();
    float sp = 0.0f, sv = 0.0f;
    for (int d = 0; d < kp_; ++d) sp += (x[d] - y[d]) * (x[d] - y[d]);
    for (int d = kp_; d < dims(); ++d) sv += (x[d] - y[d]) * (x[d] - y[d]);
    return lp_ * std::sqrt(sp) + lv_ * std::sqrt(sv);
  }

 private:
  // The top principal axes of the columns of x (as columns): as many as hold all but 1e-4 of the
  // variance, at least 2, at most kMaxAxes (and the dimension).
  static Eigen::MatrixXd principal_axes(const Eigen::MatrixXd& x, const Eigen::VectorXd& mean);

  static constexpr Eigen::Index kMaxAxes = 8;
  const PoseFeatures& features_;
  const GraphParams& params_;
  int n_ = 0, dims_ = 0, padded_ = 0, kp_ = 0;
  float lp_ = 1, lv_ = 1, abs_error_ = 0;
  Eigen::MatrixXf feat_;  // [positions, padded; velocities, padded] x slots
  Eigen::MatrixXf proj_;  // projections x slots
  Eigen::VectorXd mean_p_, mean_v_;
  std::vector<int> slot_;  // frame -> slot; empty = identity
};

}  // namespace gmg::neighbours
