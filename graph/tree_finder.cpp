#include "graph/tree_finder.h"

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

class TreeFinder : public CandidateFinder {
 public:
  TreeFinder(const PoseFeatures& f, const std::vector<double>& theta, const GraphParams& params, int workers)
      : space_(f, params),
        theta_(theta),
        allowed_{params.l_pn, params.exclude_near},
        k_(static_cast<std::size_t>(candidate_limit(params))),
        max_checks_(params.ann_checks),
        workers_(workers) {
    const int n = space_.frames();
    order_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) order_[static_cast<std::size_t>(i)] = i;
    if (n > 0) build(0, n);
    space_.set_order(order_);
  }

  int block_size() const override { return 256; }

  void next(int first, int count, Lists& out) override {
    out.assign(static_cast<std::size_t>(count), {});
    if (scratch_.size() < static_cast<std::size_t>(workers_)) scratch_.resize(static_cast<std::size_t>(workers_));
    constexpr int kChunk = 8;
    parallel_for(static_cast<std::size_t>((count + kChunk - 1) / kChunk), workers_, [&](std::size_t chunk, int worker) {
      const int begin = static_cast<int>(chunk) * kChunk;
      for (int i = begin; i < std::min(count, begin + kChunk); ++i)
        query(first + i, scratch_[static_cast<std::size_t>(worker)], out[static_cast<std::size_t>(i)]);
    });
  }

 private:
  static constexpr int kLeaf = 24;

  struct Node {
    int begin, end;             // range of order_ (tree order)
    int left = -1, right = -1;  // children; -1 for a leaf
  };

  struct Scratch {
    std::vector<std::pair<float, int>> heap;  // open nodes by lower bound (min-heap)
    std::vector<float> kth;                   // the k smallest member distances (max-heap)
  };

  int build(int begin, int end) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back({begin, end});
    const int dims = space_.dims();
    Eigen::VectorXf lo = Eigen::VectorXf::Constant(dims, std::numeric_limits<float>::max());
    Eigen::VectorXf hi = Eigen::VectorXf::Constant(dims, std::numeric_limits<float>::lowest());
    for (int i = begin; i < end; ++i) {
      const auto p = space_.projections().col(order_[static_cast<std::size_t>(i)]);
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    lo_.insert(lo_.end(), lo.data(), lo.data() + dims);
    hi_.insert(hi_.end(), hi.data(), hi.data() + dims);
    if (end - begin <= kLeaf) return id;
    // Split the widest side (weighted as the distance weighs it) at the median.
    int split = 0;
    float widest = -1.0f;
    for (int d = 0; d < dims; ++d) {
      const float w = (hi(d) - lo(d)) * (d < space_.position_dims() ? space_.lambda_pos() : space_.lambda_vel());
      if (w > widest) widest = w, split = d;
    }
    const int mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int a, int b) { return space_.projections()(split, a) < space_.projections()(split, b); });
    const int left = build(begin, mid);
    const int right = build(mid, end);
    nodes_[static_cast<std::size_t>(id)].left = left;
    nodes_[static_cast<std::size_t>(id)].right = right;
    return id;
  }

  // Lower bound of d(l, r) for every r in the node's box; q = l's projections.
  float box_bound(int node, const float* q) const {
    const int dims = space_.dims(), kp = space_.position_dims();
    const float* lo = lo_.data() + static_cast<std::size_t>(node) * static_cast<std::size_t>(dims);
    const float* hi = hi_.data() + static_cast<std::size_t>(node) * static_cast<std::size_t>(dims);
    float sp = 0.0f, sv = 0.0f;
    for (int d = 0; d < dims; ++d) {
      const float gap = std::max(std::max(lo[d] - q[d], q[d] - hi[d]), 0.0f);
      (d < kp ? sp : sv) += gap * gap;
    }
    return space_.lambda_pos() * std::sqrt(sp) + space_.lambda_vel() * std::sqrt(sv);
  }

  void query(int l, Scratch& s, std::vector<int>& out) const {
    out.clear();
    Gathered g(space_.radius(theta_[static_cast<std::size_t>(l)]), 0);
    if (g.radius() < 0) return;
    const int slot = space_.slot(l);
    const float* q = space_.projections().col(slot).data();
    float radius = g.radius();
    s.heap.clear();
    s.kth.clear();
    auto later = [](const std::pair<float, int>& a, const std::pair<float, int>& b) { return a > b; };
    s.heap.emplace_back(box_bound(0, q), 0);
    long checks = 0;
    while (!s.heap.empty()) {
      std::pop_heap(s.heap.begin(), s.heap.end(), later);
      const auto [bound, id] = s.heap.back();
      s.heap.pop_back();
      if (bound > radius) break;
      const Node& node = nodes_[static_cast<std::size_t>(id)];
      if (node.left >= 0) {
        for (const int child : {node.left, node.right}) {
          const float b = box_bound(child, q);
          if (b <= radius) {
            s.heap.emplace_back(b, child);
            std::push_heap(s.heap.begin(), s.heap.end(), later);
          }
        }
        continue;
      }
      checks += node.end - node.begin;
      for (int i = node.begin; i < node.end; ++i) {
        const int r = order_[static_cast<std::size_t>(i)];
        if (!allowed_(l, r) || space_.lower_bound_slots(i, slot) > radius) continue;
        const float d = space_.approx_slots(slot, i);
        if (d > radius || !space_.within(l, r, d, theta_[static_cast<std::size_t>(l)])) continue;
        g.add(space_, d, r);
        if (k_) radius = shrink(s, d, radius);
      }
      if (max_checks_ > 0 && checks >= max_checks_) break;
    }
    // Members found before the radius shrank may lie beyond it now.
    Gathered kept(radius, k_);
    kept.merge(space_, g);
    kept.resolve(space_, l, out);
  }

  // Tracks the k smallest member distances; the radius shrinks to the k-th plus float error.
  float shrink(Scratch& s, float d, float radius) const {
    if (s.kth.size() < k_) {
      s.kth.push_back(d);
      std::push_heap(s.kth.begin(), s.kth.end());
    } else if (d < s.kth.front()) {
      std::pop_heap(s.kth.begin(), s.kth.end());
      s.kth.back() = d;
      std::push_heap(s.kth.begin(), s.kth.end());
    }
    if (s.kth.size() < k_) return radius;
    const float kth = s.kth.front();
    return std::min(radius, kth + 2.02f * space_.error(kth));
  }

  PoseSpace space_;
  const std::vector<double>& theta_;
  Allowed allowed_;
  std::size_t k_;
  long max_checks_;
  int workers_;
  std::vector<int> order_;  // frames in tree order
  std::vector<Node> nodes_;
  std::vector<float> lo_, hi_;  // every node's box (dims floats per node)
  mutable std::vector<Scratch> scratch_;
};

}  // namespace

std::unique_ptr<CandidateFinder> make_tree_finder(const PoseFeatures& features, const std::vector<double>& theta,
                                                  const GraphParams& params, int workers) {
  return std::make_unique<TreeFinder>(features, theta, params, workers);
}

}  // namespace gmg::neighbours
