// Graph construction: pose features, break detection, continuity analysis with pruning.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <future>
#include <thread>

#include <Eigen/Eigenvalues>

#include "engine/core/error.h"
#include "graph/motion_graph.h"

namespace gmg {

std::vector<int> MotionGraph::key_frames() const {
  std::vector<int> out;
  for (int f = 0; f < frame_count(); ++f)
    if (is_key(f)) out.push_back(f);
  return out;
}

PoseFeatures pose_features(const Motion& m) {
  PoseFeatures f;
  f.positions = motion_forward_kinematics(m);
  const int dims = static_cast<int>(f.positions.cols());
  for (int j = 0; j < dims / 3; ++j) f.positions.middleCols(3 * j, 3) -= f.positions.leftCols(3);
  f.positions.leftCols(3).setZero();  // root minus itself; kept so joint j stays at columns 3j..3j+2
  f.velocities.resize(f.positions.rows(), dims);
  if (m.frame_count >= 2) {
    f.velocities.bottomRows(m.frame_count - 1) =
        f.positions.bottomRows(m.frame_count - 1) - f.positions.topRows(m.frame_count - 1);
    f.velocities.row(0) = f.velocities.row(1);
  } else if (m.frame_count == 1) {
    f.velocities.setZero();
  }
  return f;
}

double pose_distance(const PoseFeatures& f, int l, int r, const GraphParams& params) {
  return params.lambda_pos * (f.positions.row(l) - f.positions.row(r)).norm() +
         params.lambda_vel * (f.velocities.row(l) - f.velocities.row(r)).norm();
}

std::vector<int> capture_jump_frames(const PoseFeatures& f, const GraphParams& params) {
  const int n = static_cast<int>(f.positions.rows());
  std::vector<int> out;
  if (n < 3) return out;
  std::vector<double> d(static_cast<std::size_t>(n - 1));
  // Positions only: a teleport also spikes the velocity term at the next frame, which would
  // mark two breaks for one jump.
  for (int i = 0; i + 1 < n; ++i) d[i] = (f.positions.row(i) - f.positions.row(i + 1)).norm();
  std::vector<double> sorted = d;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  if (median <= 0.0) return out;  // a frozen clip has no jumps to speak of
  for (int i = 0; i + 1 < n; ++i)
    if (d[i] > params.break_jump_factor * median) out.push_back(i);
  return out;
}

namespace {

// Candidate right frames of one left frame, in frame order.
struct Candidate {
  int to;  // the right frame; its weight is computed only if it survives pruning
};

// The exact distance test of every pair, organised so that it never holds an N x N matrix:
// the features z = [lambda_pos * p, lambda_vel * v] are projected on their top principal axes
// (an orthonormal projection), and ||E^T (z_l - z_r)|| <= ||z_l - z_r|| <= d(l, r) bounds the
// distance from below. Blocks of left frames get the projected distances to all frames from one
// matrix product; only the pairs whose bound is within the threshold get the exact distance.
class DistanceFilter {
 public:
  DistanceFilter(const PoseFeatures& f, const GraphParams& params) : params_(params) {
    const Eigen::Index n = f.positions.rows();
    const Eigen::Index dims = f.positions.cols();
    pos_t_ = f.positions.transpose();
    vel_t_ = f.velocities.transpose();
    pos_tf_ = pos_t_.cast<float>();
    vel_tf_ = vel_t_.cast<float>();
    Eigen::MatrixXd z(n, 2 * dims);
    z << params.lambda_pos * f.positions, params.lambda_vel * f.velocities;
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
    projected_ = (z * basis).cast<float>();      // n x k
    projected_t_ = projected_.transpose();       // k x n, for the block products
    norms_ = projected_.rowwise().squaredNorm();
  }

  double exact(int l, int r) const {
    return params_.lambda_pos * (pos_t_.col(l) - pos_t_.col(r)).norm() +
           params_.lambda_vel * (vel_t_.col(l) - vel_t_.col(r)).norm();
  }

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
              std::vector<std::vector<Candidate>>& out) const {
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
        out[static_cast<std::size_t>(i)].push_back({r});
      }
    }
  }

 private:
  static constexpr Eigen::Index kProjectedDims = 24;
  const GraphParams& params_;
  Eigen::MatrixXd pos_t_, vel_t_;
  Eigen::MatrixXf pos_tf_, vel_tf_;
  Eigen::MatrixXf projected_, projected_t_;
  Eigen::VectorXf norms_;
};

// Pruning 1 (SPEC "Edges"): in each run of consecutive candidate frames keep the first and
// drop the next l_pn - 1, then keep again.
std::vector<Candidate> prune_runs(const std::vector<Candidate>& candidates, int l_pn) {
  std::vector<Candidate> kept;
  int run_position = 0;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (i > 0 && candidates[i].to == candidates[i - 1].to + 1)
      ++run_position;
    else
      run_position = 0;
    if (run_position % l_pn == 0) kept.push_back(candidates[i]);
  }
  return kept;
}

// Unnatural edges added so far, by source frame, for pruning 2.
class EdgeIndex {
 public:
  explicit EdgeIndex(int n) : targets_(static_cast<std::size_t>(n)) {}
  void add(int a, int b) { targets_[static_cast<std::size_t>(a)].push_back(b); }

  // True when an edge a -> b exists with a in [a_lo, a_hi] and b in [b_lo, b_hi]. Each
  // source's targets are added in ascending order (survivors of one left frame come sorted),
  // so a binary search per source answers it.
  bool any(int a_lo, int a_hi, int b_lo, int b_hi) const {
    const int n = static_cast<int>(targets_.size());
    for (int a = std::max(0, a_lo); a <= std::min(n - 1, a_hi); ++a) {
      const std::vector<int>& t = targets_[static_cast<std::size_t>(a)];
      const auto it = std::lower_bound(t.begin(), t.end(), b_lo);
      if (it != t.end() && *it <= b_hi) return true;
    }
    return false;
  }

 private:
  std::vector<std::vector<int>> targets_;
};

}  // namespace

std::vector<Transition> continuity_analysis(const PoseFeatures& f, const std::vector<int>& run_end,
                                            const GraphParams& params) {
  const int n = static_cast<int>(f.positions.rows());
  if (static_cast<int>(run_end.size()) != n) throw Error("continuity_analysis: run_end has the wrong size");
  std::vector<Transition> edges;
  if (n < 2) return edges;
  const DistanceFilter filter(f, params);
  const int l_pn = params.l_pn;

  // theta_l: mean distance to the next (up to) l_cn frames of l's run. The last frame of a run
  // has none; it uses the previous (up to) l_cn frames instead, so clip ends can still jump on.
  std::vector<double> theta(static_cast<std::size_t>(n), 0.0);
  for (int l = 0; l < n; ++l) {
    double sum = 0.0;
    int count = 0;
    for (int k = 1; k <= params.l_cn && l + k <= run_end[l]; ++k, ++count) sum += filter.exact(l, l + k);
    if (count == 0) {
      for (int k = 1; k <= params.l_cn && l - k >= 0 && run_end[l - k] == run_end[l]; ++k, ++count)
        sum += filter.exact(l, l - k);
    }
    theta[l] = count > 0 ? sum / count : 0.0;
  }

  auto allowed = [&](int l, int r) {
    if (r == l + 1) return false;  // the natural edge (or, across a break, no edge at all)
    if (params.exclude_near && std::abs(r - l) <= l_pn) return false;
    return true;
  };

  EdgeIndex index(n);
  const int workers = static_cast<int>(std::max(1u, std::min(4u, std::thread::hardware_concurrency())));
  constexpr int kBlock = 256;
  const int step = kBlock * workers;
  using Candidates = std::vector<std::vector<Candidate>>;
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
      for (const Candidate& c : prune_runs(candidates[i], l_pn)) {
        const int r = c.to;
        if (index.any(l - l_pn, l + l_pn, r - l_pn, r + l_pn) || index.any(r - l_pn, r + l_pn, l - l_pn, l + l_pn))
          continue;
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

MotionGraph graph_build(std::vector<ClipEvents> clips, const GraphParams& params) {
  if (clips.empty()) throw Error("graph build: no reference clip given");
  MotionGraph g;
  g.params = params;
  const Motion& first = clips.front().motion;
  int total = 0;
  for (const ClipEvents& c : clips) {
    std::string why;
    if (!skeletons_match(first.skeleton, c.motion.skeleton, &why))
      throw Error(c.name + ": skeleton differs from " + clips.front().name + "'s: " + why);
    if (std::abs(c.motion.fps - first.fps) > 1e-6)
      throw Error(c.name + ": " + std::to_string(c.motion.fps) + " fps differs from " + clips.front().name + "'s " +
                  std::to_string(first.fps) + " fps");
    if (c.motion.frame_count < 2) throw Error(c.name + ": a reference clip needs at least 2 frames");
    total += c.motion.frame_count;
  }

  g.motion = motion_rest(first.skeleton, first.fps, 0);
  g.motion.frame_count = total;
  PoseFeatures features;
  features.positions.resize(total, 3 * first.joint_count());
  features.velocities.resize(total, 3 * first.joint_count());
  g.graph = GraphStorage(static_cast<std::size_t>(total));
  std::vector<int> run_end(static_cast<std::size_t>(total));

  int offset = 0;
  for (ClipEvents& c : clips) {
    const Motion& m = c.motion;
    g.clips.push_back({c.name, offset, m.frame_count});
    g.motion.rotations.insert(g.motion.rotations.end(), m.rotations.begin(), m.rotations.end());
    g.motion.translations.insert(g.motion.translations.end(), m.translations.begin(), m.translations.end());
    const PoseFeatures cf = pose_features(m);
    features.positions.middleRows(offset, m.frame_count) = cf.positions;
    features.velocities.middleRows(offset, m.frame_count) = cf.velocities;

    std::vector<int> breaks = capture_jump_frames(cf, params);
    breaks.push_back(m.frame_count - 1);
    for (int b : breaks) g.graph[static_cast<std::size_t>(offset + b)].kinds |= kBreakNode;
    for (int f : c.onset_frames) {
      if (f < 0 || f >= m.frame_count) throw Error(c.name + ": onset frame " + std::to_string(f) + " outside the clip");
      g.graph[static_cast<std::size_t>(offset + f)].kinds |= kOnsetNode;
    }
    for (const auto& [f, word] : c.keyword_frames) {
      if (f < 0 || f >= m.frame_count) throw Error(c.name + ": keyword frame " + std::to_string(f) + " outside the clip");
      NodeInfo& node = g.graph[static_cast<std::size_t>(offset + f)];
      if (node.kinds & kKeywordNode) continue;  // one label per node: the first keyword wins
      node.kinds |= kKeywordNode;
      node.keyword = word;
    }
    offset += m.frame_count;
    c.motion = Motion();  // release the clip's copy early
  }

  // Natural edges inside continuous runs; run_end for the continuity analysis.
  int end = total - 1;
  for (int f = total - 1; f >= 0; --f) {
    if (g.node(f).kinds & kBreakNode) end = f;
    run_end[static_cast<std::size_t>(f)] = end;
  }
  for (int f = 0; f + 1 < total; ++f)
    if (!(g.node(f).kinds & kBreakNode))
      boost::add_edge(static_cast<std::size_t>(f), static_cast<std::size_t>(f + 1), EdgeInfo{0.0, true}, g.graph);

  for (const Transition& t : continuity_analysis(features, run_end, params))
    boost::add_edge(static_cast<std::size_t>(t.from), static_cast<std::size_t>(t.to), EdgeInfo{t.weight, false}, g.graph);
  return g;
}

GraphStats graph_stats(const MotionGraph& g) {
  GraphStats s;
  s.frames = g.frame_count();
  s.clips = static_cast<int>(g.clips.size());
  std::vector<char> has_transition(static_cast<std::size_t>(s.frames), 0);
  for (auto [it, end] = boost::edges(g.graph); it != end; ++it) {
    if (g.graph[*it].natural) {
      ++s.natural_edges;
    } else {
      ++s.unnatural_edges;
      has_transition[boost::source(*it, g.graph)] = 1;
    }
  }
  int previous_key = -1;
  s.shortest_subsequence = 0;
  for (int f = 0; f < s.frames; ++f) {
    const NodeInfo& n = g.node(f);
    if (n.kinds & kOnsetNode) ++s.onset_nodes;
    if (n.kinds & kKeywordNode) ++s.keyword_nodes;
    if (n.kinds & kBreakNode) ++s.break_nodes;
    if (n.kinds) {
      ++s.key_nodes;
      if (previous_key >= 0) {
        const int len = f - previous_key;
        s.shortest_subsequence = s.shortest_subsequence == 0 ? len : std::min(s.shortest_subsequence, len);
        s.longest_subsequence = std::max(s.longest_subsequence, len);
      }
      previous_key = f;
    }
  }
  if (s.frames > 0) {
    s.mean_out_degree = static_cast<double>(s.natural_edges + s.unnatural_edges) / s.frames;
    s.share_with_transition =
        static_cast<double>(std::count(has_transition.begin(), has_transition.end(), 1)) / s.frames;
  }
  return s;
}

}  // namespace gmg
