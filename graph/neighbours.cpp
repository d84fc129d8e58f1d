#include "graph/neighbours.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "engine/core/parallel.h"

namespace gmg {
namespace {

// The candidate search's own bound on threads (see candidate_search_workers).
constexpr int kMaxCandidateWorkers = 4;

struct Candidate {
  float d;  // d(l, r) in single precision
  int r;
};

// The pose features in single precision (centred, so that float rounding stays small against
// the distances) and their projections on the top principal axes of positions and of
// velocities. For an orthonormal projection E, ||E^T x|| <= ||x||, so
//   lambda_pos ||E_p^T (p_l - p_r)|| + lambda_vel ||E_v^T (v_l - v_r)|| <= d(l, r):
// the lower bound both searches prune with. Columns are stored in slots, frame order unless
// set_order() put them in a search tree's order (so a leaf's frames are contiguous in memory).
class PoseSpace {
 public:
  PoseSpace(const PoseFeatures& f, const GraphParams& params) : features_(f), params_(params) {
    n_ = f.frame_count();
    dims_ = static_cast<int>(f.positions.rows());
    lp_ = static_cast<float>(params.lambda_pos);
    lv_ = static_cast<float>(params.lambda_vel);
    // (No centred copy of the features is made: at an hour of reference that is 130 MB.)
    mean_p_ = f.positions.rowwise().mean();
    mean_v_ = f.velocities.rowwise().mean();
    const Eigen::MatrixXd ep = principal_axes(f.positions, mean_p_), ev = principal_axes(f.velocities, mean_v_);
    kp_ = static_cast<int>(ep.cols());
    proj_.resize(ep.cols() + ev.cols(), n_);
    proj_.topRows(ep.cols()) = ((ep.transpose() * f.positions).colwise() - ep.transpose() * mean_p_).cast<float>();
    proj_.bottomRows(ev.cols()) = ((ev.transpose() * f.velocities).colwise() - ev.transpose() * mean_v_).cast<float>();
  }

  // Fills the single-precision features with frame order[s] in slot s (frame order when
  // `order` is empty); the projections follow. Call once, before any distance.
  void set_order(const std::vector<int>& order) {
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
  static Eigen::MatrixXd principal_axes(const Eigen::MatrixXd& x, const Eigen::VectorXd& mean) {
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

// The candidates gathered for one frame: members only (d(l, r) <= theta_l, decided exactly) and,
// with a bound k, a shrinking radius: once k members are in, none farther than the k-th (plus
// float error) can belong to K_l.
class Gathered {
 public:
  Gathered() = default;
  Gathered(float radius, std::size_t k) : radius_(radius), k_(k) {}
  float radius() const { return radius_; }
  const std::vector<Candidate>& items() const { return items_; }
  void clear() { items_ = {}; }

  void add(const PoseSpace& s, float d, int r) {
    items_.push_back({d, r});
    if (k_ && items_.size() >= 2 * k_ + 32) compact(s);
  }

  // Takes the members of another gathering of the same frame.
  void merge(const PoseSpace& s, const Gathered& other) {
    radius_ = std::min(radius_, other.radius_);
    for (const Candidate& c : other.items_)
      if (c.d <= radius_) add(s, c.d, c.r);
  }

  // K_l, ascending (see neighbours.h).
  void resolve(const PoseSpace& s, int l, std::vector<int>& out) {
    out.clear();
    if (k_ && items_.size() > k_) select(s, l);
    for (const Candidate& c : items_) out.push_back(c.r);
    std::sort(out.begin(), out.end());
  }

 private:
  float kth_radius(const PoseSpace& s, float kth) const { return kth + 2.02f * s.error(kth); }

  void compact(const PoseSpace& s) {
    std::nth_element(items_.begin(), items_.begin() + static_cast<std::ptrdiff_t>(k_ - 1), items_.end(),
                     [](const Candidate& a, const Candidate& b) { return a.d < b.d; });
    radius_ = std::min(radius_, kth_radius(s, items_[k_ - 1].d));
    items_.erase(std::remove_if(items_.begin(), items_.end(), [&](const Candidate& c) { return c.d > radius_; }),
                 items_.end());
  }

  // Keeps the k nearest by (d in double, r): those clearly nearer than the k-th float distance,
  // and the best of those within float error of it, ranked in double.
  void select(const PoseSpace& s, int l) {
    std::sort(items_.begin(), items_.end(), [](const Candidate& a, const Candidate& b) { return a.d < b.d; });
    const float kth = items_[k_ - 1].d;
    const float lo = kth - 2.02f * s.error(kth), hi = kth_radius(s, kth);
    std::size_t sure = 0;
    while (sure < items_.size() && items_[sure].d < lo) ++sure;
    std::vector<std::pair<double, int>> unsure;
    for (std::size_t i = sure; i < items_.size() && items_[i].d <= hi; ++i)
      unsure.emplace_back(s.exact(l, items_[i].r), items_[i].r);
    std::sort(unsure.begin(), unsure.end());
    items_.resize(sure);
    for (std::size_t i = 0; i < unsure.size() && items_.size() < k_; ++i) items_.push_back({0.0f, unsure[i].second});
  }

  std::vector<Candidate> items_;
  float radius_ = -1.0f;
  std::size_t k_ = 0;
};

using Lists = std::vector<std::vector<int>>;

// Whether l -> r may be a transition: not itself, not the natural successor (or, across a break,
// nothing), not a stutter within l_pn when exclude_near.
struct Allowed {
  int l_pn;
  bool exclude_near;
  bool operator()(int l, int r) const {
    if (r == l || r == l + 1) return false;
    return !exclude_near || std::abs(r - l) > l_pn;
  }
};

// The exact search: tiles of left block x right block, right blocks from the left block on, so
// every pair is bounded once and serves both of its directions. A tile's bound is the distance
// of the weighted projections y = [lambda_pos E_p^T p, lambda_vel E_v^T v], whose square
// (lambda_pos a)^2 + (lambda_vel b)^2 is below d^2 = (lambda_pos a + lambda_vel b)^2: one matrix
// product and no square root per pair. Pairs within reach then get the tighter bound and d.
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

// A k-d tree over the projections, searched best first: a node's box gives a lower bound of the
// distance to every frame in it, so the search stops when the nearest unopened box is beyond the
// frame's radius (exact), or after max_checks distance evaluations (approximate).
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

NeighbourSearch neighbour_search_for(const GraphParams& params, int frames) {
  if (params.neighbours != NeighbourSearch::Auto) return params.neighbours;
  return frames <= params.exact_frames ? NeighbourSearch::Exact : NeighbourSearch::Approximate;
}

int graph_transition_bound(const GraphParams& params, int frames) {
  const bool small = params.neighbours == NeighbourSearch::Auto && frames <= params.exact_frames;
  return small ? 0 : params.max_transitions;
}

int candidate_search_workers() { return std::min(kMaxCandidateWorkers, worker_count(0)); }

int candidate_limit(const GraphParams& params) {
  if (params.max_transitions == 0) return 0;
  const long long k = static_cast<long long>(params.max_transitions) * params.candidates_per_transition;
  return static_cast<int>(std::min<long long>(k, std::numeric_limits<int>::max()));
}

std::unique_ptr<CandidateFinder> make_candidate_finder(const PoseFeatures& features, const std::vector<double>& theta,
                                                       const GraphParams& params, NeighbourSearch search, int workers) {
  workers = std::max(1, workers);
  if (search == NeighbourSearch::Auto) search = neighbour_search_for(params, features.frame_count());
  if (search == NeighbourSearch::Exact) return std::make_unique<ExactFinder>(features, theta, params, workers);
  return std::make_unique<TreeFinder>(features, theta, params, workers);
}

std::vector<std::vector<int>> candidate_sets(const PoseFeatures& features, const std::vector<double>& theta,
                                             const GraphParams& params, NeighbourSearch search) {
  const int n = features.frame_count();
  const std::unique_ptr<CandidateFinder> finder =
      make_candidate_finder(features, theta, params, search, candidate_search_workers());
  std::vector<std::vector<int>> all, block;
  for (int first = 0; first < n; first += finder->block_size()) {
    finder->next(first, std::min(finder->block_size(), n - first), block);
    for (auto& b : block) all.push_back(std::move(b));
  }
  return all;
}

double candidate_recall(const std::vector<std::vector<int>>& found, const std::vector<std::vector<int>>& exact) {
  std::size_t total = 0, hit = 0;
  for (std::size_t l = 0; l < exact.size(); ++l) {
    total += exact[l].size();
    if (l >= found.size()) continue;
    for (const int r : exact[l]) hit += std::binary_search(found[l].begin(), found[l].end(), r) ? 1 : 0;
  }
  return total == 0 ? 1.0 : static_cast<double>(hit) / static_cast<double>(total);
}

}  // namespace gmg
