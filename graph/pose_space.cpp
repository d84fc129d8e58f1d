#include "graph/pose_space.h"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "engine/core/error.h"

namespace gmg::neighbours {

PoseSpace::PoseSpace(const FeatureStore& store, const GraphParams& params) : store_(&store), params_(params) {
  start();
}

PoseSpace::PoseSpace(std::unique_ptr<FeatureStore> owned, const GraphParams& params)
    : owned_(std::move(owned)), store_(owned_.get()), params_(params) {
  start();
}

PoseSpace::PoseSpace(const PoseFeatures& f, const GraphParams& params) : PoseSpace(FeatureStore::of(f), params) {
  add_clip(f);
  finish();
}

void PoseSpace::start() {
  const int dims = store_->dims();
  dims_ = dims;
  padded_ = (dims_ + 15) / 16 * 16;
  positions_ = RowChunks(static_cast<std::size_t>(padded_));
  lp_ = static_cast<float>(params_.lambda_pos);
  lv_ = static_cast<float>(params_.lambda_vel);
  sum_p_ = Eigen::VectorXd::Zero(dims_);
  sum_v_ = Eigen::VectorXd::Zero(dims_);
  outer_p_ = Eigen::MatrixXd::Zero(dims_, dims_);
  outer_v_ = Eigen::MatrixXd::Zero(dims_, dims_);
}

void PoseSpace::add_clip(const PoseFeatures& clip) {
  const int m = clip.frame_count();
  if (clip.positions.rows() != dims_) throw Error("PoseSpace: a clip with another joint count");
  if (n_ == 0) mean_p_ = clip.positions.rowwise().mean();
  positions_.resize(static_cast<std::size_t>(n_) + static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) {
    float* p = positions_.row(static_cast<std::size_t>(n_ + i));
    for (int d = 0; d < dims_; ++d) p[d] = static_cast<float>(clip.positions(d, i) - mean_p_(d));
  }
  // (The whole clip's products at once: for a graph of one clip, the same sums as over all frames.)
  sum_p_ += clip.positions.rowwise().sum();
  sum_v_ += clip.velocities.rowwise().sum();
  outer_p_ += clip.positions * clip.positions.transpose();
  outer_v_ += clip.velocities * clip.velocities.transpose();
  n_ += m;
}

void PoseSpace::finish() {
  if (n_ != store_->frame_count()) throw Error("PoseSpace: its clips are not the feature store's");
  const double n = std::max(1.0, static_cast<double>(n_));
  const Eigen::VectorXd mp = sum_p_ / n, mv = sum_v_ / n;
  const Eigen::MatrixXd ep = principal_axes(outer_p_ / n - mp * mp.transpose());
  const Eigen::MatrixXd ev = principal_axes(outer_v_ / n - mv * mv.transpose());
  outer_p_ = Eigen::MatrixXd();
  outer_v_ = Eigen::MatrixXd();
  kp_ = static_cast<int>(ep.cols());
  kv_ = static_cast<int>(ev.cols());
  // Projections of the float positions and velocities, a few thousand frames at a time.
  proj_ = Eigen::MatrixXf::Zero(kProjections, n_);
  constexpr int kChunk = 4096;
  Eigen::MatrixXd p(dims_, kChunk), v(dims_, kChunk);
  double max_p = 0.0;
  for (int first = 0; first < n_; first += kChunk) {
    const int m = std::min(kChunk, n_ - first);
    for (int i = 0; i < m; ++i) {
      const int f = first + i;
      const auto [a, b] = store_->velocity_frames(f);
      const float* x = position(f);
      const float* xa = position(a);
      const float* xb = position(b);
      double norm = 0.0;
      for (int d = 0; d < dims_; ++d) {
        p(d, i) = x[d];
        v(d, i) = static_cast<double>(xa[d] - xb[d]);
        norm += static_cast<double>(x[d]) * x[d];
      }
      max_p = std::max(max_p, std::sqrt(norm));
    }
    proj_.block(0, first, kp_, m) = (ep.transpose() * p.leftCols(m)).cast<float>();
    proj_.block(8, first, kv_, m) = (ev.transpose() * v.leftCols(m)).cast<float>();
  }
  // Float rounding moves a position by at most 6e-8 of the largest centred position, and a
  // velocity (the difference of two rounded positions, rounded) by at most about 3 times that;
  // the sums of squares move the norms by about dims x 6e-8 of themselves. 1e-4 relative
  // (error()) and 1e-5 x (lambda_pos + 4 lambda_vel) of the largest position absolute leave a
  // wide margin.
  abs_error_ = static_cast<float>(1e-5 * (params_.lambda_pos + 4.0 * params_.lambda_vel) * max_p) + 1e-30f;
}

void PoseSpace::set_order(const std::vector<int>& order, long long max_row_bytes) {
  if (order.empty()) return;
  Eigen::MatrixXf proj(proj_.rows(), n_);
  slot_.assign(static_cast<std::size_t>(n_), 0);
  for (int s = 0; s < n_; ++s) {
    proj.col(s) = proj_.col(order[static_cast<std::size_t>(s)]);
    slot_[static_cast<std::size_t>(order[static_cast<std::size_t>(s)])] = s;
  }
  proj_.swap(proj);
  const long long bytes = 2LL * padded_ * static_cast<long long>(sizeof(float)) * n_;
  if (bytes > max_row_bytes) return;
  rows_ = RowChunks(2 * static_cast<std::size_t>(padded_));
  rows_.resize(static_cast<std::size_t>(n_));
  for (int s = 0; s < n_; ++s) {
    const int f = order[static_cast<std::size_t>(s)];
    const auto [a, b] = store_->velocity_frames(f);
    float* row = rows_.row(static_cast<std::size_t>(s));
    const float* x = position(f);
    const float* xa = position(a);
    const float* xb = position(b);
    for (int d = 0; d < padded_; ++d) {
      row[d] = x[d];
      row[padded_ + d] = xa[d] - xb[d];
    }
  }
  positions_ = RowChunks(static_cast<std::size_t>(padded_));
}

Eigen::MatrixXd PoseSpace::principal_axes(const Eigen::MatrixXd& cov) {
  const Eigen::Index dims = cov.rows();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(cov);
  const Eigen::VectorXd values = solver.eigenvalues().reverse();
  const double total = std::max(values.sum(), 1e-300);
  Eigen::Index k = 0;
  double held = 0.0;
  while (k < dims && k < kMaxAxes && (k < 2 || held < (1.0 - 1e-4) * total)) held += std::max(0.0, values(k++));
  return solver.eigenvectors().rightCols(k).rowwise().reverse();
}

}  // namespace gmg::neighbours
