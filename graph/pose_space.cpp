#include "graph/pose_space.h"

#include <algorithm>

#include <Eigen/Eigenvalues>

namespace gmg::neighbours {

PoseSpace::PoseSpace(const PoseFeatures& f, const GraphParams& params) : features_(f), params_(params) {
  n_ = f.frame_count();
  dims_ = static_cast<int>(f.positions.rows());
  lp_ = static_cast<float>(params.lambda_pos);
  lv_ = static_cast<float>(params.lambda_vel);
  // (No centred copy of the features is made: at an hour of reference that is 130 MB.)
  mean_p_ = f.positions.rowwise().mean();
  mean_v_ = f.velocities.rowwise().mean();
  const Eigen::MatrixXd ep = principal_axes(f.positions, mean_p_), ev = principal_axes(f.velocities, mean_v_);
  kp_ = static_cast<int>(ep.cols());
  kv_ = static_cast<int>(ev.cols());
  proj_ = Eigen::MatrixXf::Zero(kProjections, n_);
  proj_.topRows(kp_) = ((ep.transpose() * f.positions).colwise() - ep.transpose() * mean_p_).cast<float>();
  proj_.middleRows(8, kv_) = ((ev.transpose() * f.velocities).colwise() - ev.transpose() * mean_v_).cast<float>();
}

void PoseSpace::set_order(const std::vector<int>& order) {
  if (!order.empty()) {
    Eigen::MatrixXf proj(proj_.rows(), n_);
    slot_.assign(static_cast<std::size_t>(n_), 0);
    for (int s = 0; s < n_; ++s) {
      proj.col(s) = proj_.col(order[static_cast<std::size_t>(s)]);
      slot_[static_cast<std::size_t>(order[static_cast<std::size_t>(s)])] = s;
    }
    proj_.swap(proj);
  }
  // Each part padded with zeros to a multiple of 16 floats: distances then run in whole SIMD
  // packets on aligned columns.
  padded_ = (dims_ + 15) / 16 * 16;
  feat_ = Eigen::MatrixXf::Zero(2 * static_cast<Eigen::Index>(padded_), n_);
  for (int s = 0; s < n_; ++s) {
    const int f = order.empty() ? s : order[static_cast<std::size_t>(s)];
    feat_.col(s).head(dims_) = (features_.positions.col(f) - mean_p_).cast<float>();
    feat_.col(s).segment(padded_, dims_) = (features_.velocities.col(f) - mean_v_).cast<float>();
  }
  // Float rounding of the inputs moves a norm by at most ~1.2e-7 of the features' largest norm
  // per term, and the sums by ~dims * 6e-8 of the result: 1e-4 relative and 1e-5 of the largest
  // norms absolute leave a wide margin.
  const float max_p = n_ ? feat_.topRows(padded_).colwise().norm().maxCoeff() : 0.0f;
  const float max_v = n_ ? feat_.bottomRows(padded_).colwise().norm().maxCoeff() : 0.0f;
  abs_error_ = 1e-5f * (lp_ * max_p + lv_ * max_v) + 1e-30f;
}

Eigen::MatrixXd PoseSpace::principal_axes(const Eigen::MatrixXd& x, const Eigen::VectorXd& mean) {
  const Eigen::Index dims = x.rows();
  const Eigen::MatrixXd cov = x * x.transpose() / std::max<double>(1.0, double(x.cols())) - mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(cov);
  const Eigen::VectorXd values = solver.eigenvalues().reverse();
  const double total = std::max(values.sum(), 1e-300);
  Eigen::Index k = 0;
  double held = 0.0;
  while (k < dims && k < kMaxAxes && (k < 2 || held < (1.0 - 1e-4) * total)) held += std::max(0.0, values(k++));
  return solver.eigenvectors().rightCols(k).rowwise().reverse();
}

}  // namespace gmg::neighbours
