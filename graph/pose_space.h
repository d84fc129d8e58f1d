// The pose space the candidate search (graph/neighbours.h) works in: the pose features in single
// precision and their principal-axis projections, with the error bounds that let a float distance
// decide a candidate only where it cannot be wrong. Internal to graph/.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "engine/core/row_chunks.h"
#include "graph/features.h"
#include "graph/float_lanes.h"
#include "graph/params.h"

namespace gmg::neighbours {

// The positions in single precision, centred on the first clip's mean (so that float rounding
// stays small against the distances), the velocities taken from them as the features take them
// (graph/features.h FeatureStore), and the projections of both on their top principal axes. For
// an orthonormal projection E, ||E^T x|| <= ||x||, so
//   lambda_pos ||E_p^T (p_l - p_r)|| + lambda_vel ||E_v^T (v_l - v_r)|| <= d(l, r):
// the lower bound the search prunes with. A frame's projections are sixteen floats, rows 0-7 the
// positions' (kp of them used), rows 8-15 the velocities' (zero where unused, which adds exactly
// nothing); their columns are in slots, frame order unless set_order() put them in a search
// tree's order. Sums run in the fixed orders of graph/float_lanes.h, so every float value is the
// same in every build. Distances in double come from the FeatureStore.
class PoseSpace {
 public:
  // Built clip by clip (add_clip with each clip's pose_features, in the order of `store`'s clips,
  // then finish()). `store` must outlive the space.
  PoseSpace(const FeatureStore& store, const GraphParams& params);
  // The features given whole (their velocities the positions' differences: FeatureStore::of).
  PoseSpace(const PoseFeatures& f, const GraphParams& params);

  void add_clip(const PoseFeatures& clip);
  void finish();

  // Puts frame order[s]'s projections in slot s (frame order when `order` is empty), and, when
  // they fit in `max_row_bytes`, the positions and velocities too (ordered_rows(): approx_slots
  // then reads them; the frame-order positions are freed). Either way approx() gives the same
  // value, bit for bit.
  void set_order(const std::vector<int>& order, long long max_row_bytes = kLeafOrderRowsBytes);

  int frames() const { return n_; }
  static constexpr int kProjections = 16;    // rows of projections(): 8 of positions, 8 of velocities
  int position_dims() const { return kp_; }  // the position rows in use (the rest are 0)
  int velocity_dims() const { return kv_; }  // the velocity rows in use, from row 8
  float lambda_pos() const { return lp_; }
  float lambda_vel() const { return lv_; }
  int slot(int frame) const { return slot_.empty() ? frame : slot_[static_cast<std::size_t>(frame)]; }
  const Eigen::MatrixXf& projections() const { return proj_; }  // kProjections x frames, by slot

  double exact(int l, int r) const { return store_->distance(l, r, params_); }
  const FeatureStore& store() const { return *store_; }
  // d(l, r) in single precision: sixteen running sums of the squared differences of the positions
  // and of the velocities (each velocity the difference of two frames' float positions), summed
  // in the fixed order.
  float approx(int l, int r) const {
    if (rows_.rows() != 0) return approx_slots(slot(l), slot(r));
    const float* pl = position(l);
    const float* pr = position(r);
    const auto [al, bl] = store_->velocity_frames(l);
    const auto [ar, br] = store_->velocity_frames(r);
    const float* val = position(al);
    const float* vbl = position(bl);
    const float* var = position(ar);
    const float* vbr = position(br);
    Sixteen sp = Sixteen::zero(), sv = Sixteen::zero();
    for (int j = 0; j < padded_; j += 16) {
      sp.add_square_of_difference(Sixteen::at(pl + j), Sixteen::at(pr + j));
      sv.add_square_of_difference(Sixteen::difference(Sixteen::at(val + j), Sixteen::at(vbl + j)),
                                  Sixteen::difference(Sixteen::at(var + j), Sixteen::at(vbr + j)));
    }
    alignas(64) float p[16], v[16];
    sp.store(p);
    sv.store(v);
    return lp_ * std::sqrt(sum16(p)) + lv_ * std::sqrt(sum16(v));
  }
  // approx() of the frames in slots a and b, read from the rows in slot order (ordered_rows()
  // only): the same floats summed in the same order, so the same value bit for bit.
  float approx_slots(int a, int b) const {
    const float* xa = rows_.row(static_cast<std::size_t>(a));
    const float* xb = rows_.row(static_cast<std::size_t>(b));
    Sixteen sp = Sixteen::zero(), sv = Sixteen::zero();
    for (int j = 0; j < padded_; j += 16) {
      sp.add_square_of_difference(Sixteen::at(xa + j), Sixteen::at(xb + j));
      sv.add_square_of_difference(Sixteen::at(xa + padded_ + j), Sixteen::at(xb + padded_ + j));
    }
    alignas(64) float p[16], v[16];
    sp.store(p);
    sv.store(v);
    return lp_ * std::sqrt(sum16(p)) + lv_ * std::sqrt(sum16(v));
  }
  // Asks for slot s's row (its positions and velocity, side by side) to be brought into cache.
  void prefetch_slot(int s) const {
    const char* row = reinterpret_cast<const char*>(rows_.row(static_cast<std::size_t>(s)));
    for (int at = 0; at < 2 * padded_ * static_cast<int>(sizeof(float)); at += 64) __builtin_prefetch(row + at);
  }
  // Whether set_order() kept the rows in slot order (approx_slots and prefetch_slot need them).
  bool ordered_rows() const { return rows_.rows() != 0; }
  // Asks for the rows approx(l, r) reads of frame r to be brought into cache: its positions and
  // the previous frame's (its velocity's other frame, except at a clip start): a leaf's frames lie
  // across the whole reference in frame order, and fetching them all before the first approx
  // overlaps their misses instead of waiting for each in turn.
  void prefetch(int r) const {
    for (int f = std::max(r - 1, 0); f <= r; ++f) {
      const char* row = reinterpret_cast<const char*>(position(f));
      for (int at = 0; at < padded_ * static_cast<int>(sizeof(float)); at += 64) __builtin_prefetch(row + at);
    }
  }
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
  // Projected lower bound of d between the frames in slots a and b. (Each sum runs over its eight
  // rows in order, as the tree's leaves compute it for sixteen frames at a time.)
  float lower_bound_slots(int a, int b) const {
    const float* x = proj_.col(a).data();
    const float* y = proj_.col(b).data();
    float sp = 0.0f, sv = 0.0f;
    for (int d = 0; d < 8; ++d) sp += (x[d] - y[d]) * (x[d] - y[d]);
    for (int d = 8; d < 16; ++d) sv += (x[d] - y[d]) * (x[d] - y[d]);
    return lp_ * std::sqrt(sp) + lv_ * std::sqrt(sv);
  }

 private:
  PoseSpace(std::unique_ptr<FeatureStore> owned, const GraphParams& params);
  void start();
  const float* position(int f) const { return positions_.row(static_cast<std::size_t>(f)); }
  // The top principal axes (as columns) of a covariance: as many as hold all but 1e-4 of the
  // variance, at least 2, at most kMaxAxes (and the dimension).
  static Eigen::MatrixXd principal_axes(const Eigen::MatrixXd& covariance);

  static constexpr Eigen::Index kMaxAxes = 8;
  std::unique_ptr<FeatureStore> owned_;  // the PoseFeatures constructor's
  const FeatureStore* store_;
  const GraphParams& params_;
  int n_ = 0, dims_ = 0, padded_ = 0, kp_ = 0, kv_ = 0;
  float lp_ = 1, lv_ = 1, abs_error_ = 0;
  RowChunks positions_;  // padded_ floats a frame, frame order
  RowChunks rows_;       // by slot: positions then velocities
  // Sums for the principal axes: of the positions and velocities, and of their outer products.
  Eigen::VectorXd mean_p_, sum_p_, sum_v_;
  Eigen::MatrixXd outer_p_, outer_v_;
  Eigen::MatrixXf proj_;   // kProjections x slots
  std::vector<int> slot_;  // frame -> slot; empty = identity
};

}  // namespace gmg::neighbours
