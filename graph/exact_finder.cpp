#include "graph/exact_finder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "engine/core/parallel.h"
#include "graph/candidate_gathering.h"
#include "graph/pose_space.h"

namespace gmg::neighbours {
namespace {

using Lists = std::vector<std::vector<int>>;

class ExactFinder : public CandidateFinder {
 public:
  ExactFinder(const PoseFeatures& f, const std::vector<double>& theta, const GraphParams& params, int workers)
      : space_(f, params),
        theta_(theta),
        allowed_{params.l_pn, params.exclude_near},
        k_(static_cast<std::size_t>(candidate_limit(params))),
        workers_(workers) {
    space_.set_order({});
    const int n = space_.frames();
    const int kp = space_.position_dims();
    weighted_ = space_.projections();
    weighted_.topRows(kp) *= space_.lambda_pos();
    weighted_.bottomRows(space_.dims() - kp) *= space_.lambda_vel();
    norms_ = weighted_.colwise().squaredNorm().transpose();
    gathered_.reserve(static_cast<std::size_t>(n));
    radius_.resize(n);
    for (int l = 0; l < n; ++l) {
      gathered_.emplace_back(space_.radius(theta[static_cast<std::size_t>(l)]), k_);
      radius_(l) = gathered_.back().radius();
    }
  }

  int block_size() const override { return kLeft; }

  void next(int first, int count, Lists& out) override {
    const int n = space_.frames();
    const int right_blocks = (n - first + kRight - 1) / kRight;
    // Left frames' members from each worker, merged after the pass (right frames beyond the
    // left block belong to the one worker whose right block holds them).
    std::vector<std::vector<Gathered>> local(static_cast<std::size_t>(workers_));
    for (auto& w : local)
      for (int i = 0; i < count; ++i) w.emplace_back(radius_(first + i), k_);
    if (tiles_.size() < static_cast<std::size_t>(workers_)) tiles_.resize(static_cast<std::size_t>(workers_));
    parallel_for(static_cast<std::size_t>(right_blocks), workers_, [&](std::size_t b, int worker) {
      const int r0 = first + static_cast<int>(b) * kRight;
      tile(first, count, r0, std::min(kRight, n - r0), local[static_cast<std::size_t>(worker)],
           tiles_[static_cast<std::size_t>(worker)]);
    });
    out.assign(static_cast<std::size_t>(count), {});
    for (int i = 0; i < count; ++i) {
      Gathered& g = gathered_[static_cast<std::size_t>(first + i)];
      for (const auto& w : local) g.merge(space_, w[static_cast<std::size_t>(i)]);
      g.resolve(space_, first + i, out[static_cast<std::size_t>(i)]);
      g.clear();
    }
  }

 private:
  static constexpr int kLeft = 256, kRight = 1024;

  // One worker's reusable buffers: a tile's products and the margins of one left frame's row.
  struct TileBuffers {
    Eigen::MatrixXf gram;
    Eigen::ArrayXf margin;
  };

  void tile(int l0, int lcount, int r0, int rcount, std::vector<Gathered>& left, TileBuffers& t) {
    t.gram.noalias() = weighted_.middleCols(r0, rcount).transpose() * weighted_.middleCols(l0, lcount);
    const auto norms = norms_.segment(r0, rcount).array();
    const auto radius = radius_.segment(r0, rcount).array();
    // Products carry a float error of about 1e-6 of the norms: the squared distances are
    // lowered by 1e-4 of the norms so the bound stays below the true distance.
    constexpr float kShrink = 1.0f - 1e-4f;
    const int skip = allowed_.exclude_near ? allowed_.l_pn : 0;
    for (int i = 0; i < lcount; ++i) {
      const int l = l0 + i;
      const int from = std::max(r0, l + 1 + skip);  // pairs l < r only; the nearest are never allowed
      if (from >= r0 + rcount) continue;
      Gathered& gl = left[static_cast<std::size_t>(i)];
      // <= 0 where the pair is within reach of one of its frames.
      t.margin = (norms_(l) + norms) * kShrink - 2.0f * t.gram.col(i).array() - radius.max(gl.radius()).square();
      const float* margin = t.margin.data() - r0;
      for (int r = from; r < r0 + rcount; ++r) {
        // Most pairs are out of reach: skip whole runs of 16 with one vector test.
        if ((r - r0) % 16 == 0 && r + 16 <= r0 + rcount) {
          bool any = false;
          for (int j = 0; j < 16; ++j) any |= margin[r + j] <= 0.0f;
          if (!any) {
            r += 15;
            continue;
          }
        }
        if (margin[r] > 0.0f) continue;
        Gathered& gr =
            r < l0 + lcount ? left[static_cast<std::size_t>(r - l0)] : gathered_[static_cast<std::size_t>(r)];
        const float lb = space_.lower_bound_slots(l, r);  // frame order: slot == frame
        const bool to_r = lb <= gl.radius() && allowed_(l, r);
        const bool to_l = lb <= gr.radius();  // r -> l with l < r is never the natural successor
        if (!to_r && !to_l) continue;
        const float d = space_.approx(l, r);
        if (to_r && d <= gl.radius() && space_.within(l, r, d, theta_[static_cast<std::size_t>(l)]))
          gl.add(space_, d, r);
        if (to_l && d <= gr.radius() && space_.within(r, l, d, theta_[static_cast<std::size_t>(r)])) {
          gr.add(space_, d, l);
          if (r >= l0 + lcount) radius_(r) = gr.radius();  // only this worker touches frame r's row
        }
      }
    }
  }

  PoseSpace space_;
  const std::vector<double>& theta_;
  Allowed allowed_;
  std::size_t k_;
  int workers_;
  Eigen::MatrixXf weighted_;        // the weighted projections, dims x frames
  Eigen::VectorXf norms_;           // their squared norms
  Eigen::VectorXf radius_;          // every frame's radius (at the start of its left block's pass)
  std::vector<Gathered> gathered_;  // every frame's members so far (complete once its block is reached)
  std::vector<TileBuffers> tiles_;
};

}  // namespace

std::unique_ptr<CandidateFinder> make_exact_finder(const PoseFeatures& features, const std::vector<double>& theta,
                                                   const GraphParams& params, int workers) {
  return std::make_unique<ExactFinder>(features, theta, params, workers);
}

}  // namespace gmg::neighbours
