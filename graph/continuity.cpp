#include "graph/continuity.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <thread>

#include <Eigen/Eigenvalues>

#include "engine/core/error.h"
#include "graph/pruning.h"

namespace gmg {
namespace {

// The exact distance test of every pair, organised so that it never holds an N x N matrix:
// the features z = [lambda_pos * p, lambda_vel * v] are projected on their top principal axes
// (an orthonormal projection), and ||E^T (z_l - z_r)|| <= ||z_l - z_r|| <= d(l, r) bounds the
// distance from below. Blocks of left frames get the projected distances to all frames from one
// matrix product; only the pairs whose bound is within the threshold get the exact distance.
class DistanceFilter {
 public:
  DistanceFilter(const PoseFeatures& f, const GraphParams& params) : features_(f), params_(params) {
    const Eigen::Index n = f.positions.cols();
    const Eigen::Index dims = f.positions.rows();
    pos_tf_ = f.positions.cast<float>();
    vel_tf_ = f.velocities.cast<float>();
    Eigen::MatrixXd z(n, 2 * dims);
    z << params.lambda_pos * f.positions.transpose(), params.lambda_vel * f.velocities.transpose();
    const Eigen::RowVectorXd mean = z.colwise().mean();
    z.rowwise() -= mean;
    const Eigen::Index k = std::min<Eigen::Index>(kProjectedDims, 2 * dims);
    Eigen::MatrixXd basis;
    if (k == 2 * dims) {
      basis = Eigen::MatrixXd::Identity(2 * dims, 2 * dims);
    } else {
      const Eigen::MatrixXd cov = (z.transpose() * z) / std::max<double>(1.0, static_cast<double>(n));
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(cov);
      basis = solver.eigenvectors().rightCols(k);  // eigenvalues ascend: the last k are largest
    }
    projected_ = (z * basis).cast<float>();  // n x k
    projected_t_ = projected_.transpose();   // k x n, for the block products
    norms_ = projected_.rowwise().squaredNorm();
  }

  double exact(int l, int r) const { return pose_distance(features_, l, r, params_); }

  // d(l, r) in single precision: half the memory traffic and twice the SIMD width of exact().
  float approximate(int l, int r) const {
    return static_cast<float>(params_.lambda_pos) * (pos_tf_.col(l) - pos_tf_.col(r)).norm() +
           static_cast<float>(params_.lambda_vel) * (vel_tf_.col(l) - vel_tf_.col(r)).norm();
  }

  // Appends to out[i] the frames r (ascending, r != l, allowed(l, r)) with d(l, r) <= theta[i]
  // for l = first + i. The test runs in float; only values within 1e-4 of the threshold are
  // decided in double, so the result is the exact one. Weights are left for the caller.
  template <typename Allowed>
  void within(int first, int count, const std::vector<double>& theta, const Allowed& allowed,
              std::vector<std::vector<int>>& out) const {
    const int n = static_cast<int>(projected_.rows());
    // n x count, column-major: the products of one left frame with all frames are contiguous.
    const Eigen::MatrixXf gram = projected_ * projected_t_.middleCols(first, count);
    Eigen::ArrayXf bound2(n);
    for (int i = 0; i < count; ++i) {
      const int l = first + i;
      const double t = theta[static_cast<std::size_t>(i)];
      if (!(t > 0.0)) continue;
      const float nl = norms_(l);
      const float t2 = static_cast<float>(t * t);
      // Float products carry a relative error of about 1e-6 of the norms: widen the bound by
      // more than that so no true candidate is lost; the exact test decides. One vectorised
      // pass computes the slack-adjusted bound of every pair, a second picks the few that pass.
      bound2 = (nl + norms_.array()) * (1.0f - 1e-4f) - 2.0f * gram.col(i).array();
      for (int r = 0; r < n; ++r) {
        if (bound2(r) > t2 + 1e-12f) continue;
        if (r == l || !allowed(l, r)) continue;
        const float approx = approximate(l, r);
        if (approx > static_cast<float>(t) * (1.0f + 1e-4f) + 1e-12f) continue;
        if (approx >= static_cast<float>(t) * (1.0f - 1e-4f) && exact(l, r) > t) continue;
        out[static_cast<std::size_t>(i)].push_back(r);
      }
    }
  }

 private:
  static constexpr Eigen::Index kProjectedDims = 24;
  const PoseFeatures& features_;
  const GraphParams& params_;
  Eigen::MatrixXf pos_tf_, vel_tf_;
  Eigen::MatrixXf projected_, projected_t_;
  Eigen::VectorXf norms_;
};

}  // namespace

std::vector<double> continuity_thresholds(const PoseFeatures& f, const std::vector<int>& run_end,
                                          const GraphParams& params) {
  const int n = f.frame_count();
  std::vector<double> theta(static_cast<std::size_t>(n), 0.0);
  for (int l = 0; l < n; ++l) {
    const int end = run_end[static_cast<std::size_t>(l)];
    double sum = 0.0;
    int count = 0;
    for (int k = 1; k <= params.l_cn && l + k <= end; ++k, ++count) sum += pose_distance(f, l, l + k, params);
    if (count == 0) {
      for (int k = 1; k <= params.l_cn && l - k >= 0 && run_end[static_cast<std::size_t>(l - k)] == end; ++k, ++count)
        sum += pose_distance(f, l, l - k, params);
    }
    theta[static_cast<std::size_t>(l)] = count > 0 ? sum / count : 0.0;
  }
  return theta;
}

std::vector<Transition> continuity_analysis(const PoseFeatures& f, const std::vector<int>& run_end,
                                            const GraphParams& params) {
  const int n = f.frame_count();
  if (static_cast<int>(run_end.size()) != n) throw Error("continuity_analysis: run_end has the wrong size");
  std::vector<Transition> edges;
  if (n < 2) return edges;
  const DistanceFilter filter(f, params);
  const int l_pn = params.l_pn;

  const std::vector<double> theta = continuity_thresholds(f, run_end, params);

  auto allowed = [&](int l, int r) {
    if (r == l + 1) return false;  // the natural edge (or, across a break, no edge at all)
    if (params.exclude_near && std::abs(r - l) <= l_pn) return false;
    return true;
  };

  EdgeIndex index(n);
  const int workers = static_cast<int>(std::max(1u, std::min(4u, std::thread::hardware_concurrency())));
  constexpr int kBlock = 256;
  const int step = kBlock * workers;
  using Candidates = std::vector<std::vector<int>>;
  // Candidates of each left frame are independent: a block of them is computed in parallel,
  // `workers` threads of kBlock frames each...
  auto compute = [&](int block) {
    const int block_count = std::min(step, n - block);
    Candidates candidates(static_cast<std::size_t>(block_count));
    std::vector<std::thread> threads;
    for (int w = 0; w < workers; ++w) {
      const int first = block + w * kBlock;
      const int count = std::min(kBlock, block + block_count - first);
      if (count <= 0) break;
      threads.emplace_back([&, first, count] {
        Candidates local(static_cast<std::size_t>(count));
        const std::vector<double> local_theta(theta.begin() + first, theta.begin() + first + count);
        filter.within(first, count, local_theta, allowed, local);
        for (int i = 0; i < count; ++i)
          candidates[static_cast<std::size_t>(first - block + i)] = std::move(local[static_cast<std::size_t>(i)]);
      });
    }
    for (std::thread& t : threads) t.join();
    return candidates;
  };
  // ...while pruning 2, which depends on the edges of earlier left frames, walks the previous
  // block in order on this thread.
  std::future<Candidates> next = std::async(std::launch::async, compute, 0);
  for (int block = 0; block < n; block += step) {
    const Candidates candidates = next.get();
    if (block + step < n) next = std::async(std::launch::async, compute, block + step);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const int l = block + static_cast<int>(i);
      for (const int r : prune_runs(candidates[i], l_pn)) {
        if (index.covers(l, r, l_pn)) continue;
        edges.push_back({l, r, filter.exact(l, r)});
      }
      // Pruning 2 looks only at earlier left frames: this frame's survivors join the index
      // after all of them were tested.
      std::size_t e = edges.size();
      while (e > 0 && edges[e - 1].from == l) --e;
      for (; e < edges.size(); ++e) index.add(l, edges[e].to);  // ascending, as EdgeIndex needs
    }
  }
  return edges;
}

}  // namespace gmg
