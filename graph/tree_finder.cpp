#include "graph/tree_finder.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

namespace gmg::neighbours {
namespace {

constexpr int kDims = PoseSpace::kProjections;
static_assert(CandidateTree::kLeaf % kLanes == 0, "a leaf is a whole number of vectors");

}  // namespace

CandidateTree::CandidateTree(PoseSpace&& space, const std::vector<double>& theta, const GraphParams& params,
                             long max_checks)
    : space_(std::move(space)),
      theta_(theta),
      allowed_{params.l_pn, params.exclude_near},
      k_(static_cast<std::size_t>(candidate_limit(params))),
      max_checks_(max_checks) {
  const int n = space_.frames();
  order_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) order_[static_cast<std::size_t>(i)] = i;
  if (n > 0) build(0, n);
  space_.set_order(order_);
  // The leaves' projections, dimension-major within each leaf.
  const std::size_t leaves = (static_cast<std::size_t>(n) + kLeaf - 1) / kLeaf;
  blocks_ = RowChunks(static_cast<std::size_t>(kDims) * kLeaf);
  blocks_.resize(leaves);
  for (int s = 0; s < n; ++s) {
    float* block = blocks_.row(static_cast<std::size_t>(s / kLeaf));
    for (int d = 0; d < kDims; ++d) block[d * kLeaf + s % kLeaf] = space_.projections()(d, s);
  }
}

int CandidateTree::build(int begin, int end) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back({begin, end});
  float lo[kDims], hi[kDims];
  std::fill(lo, lo + kDims, std::numeric_limits<float>::max());
  std::fill(hi, hi + kDims, std::numeric_limits<float>::lowest());
  for (int i = begin; i < end; ++i) {
    const float* p = space_.projections().col(order_[static_cast<std::size_t>(i)]).data();
    for (int d = 0; d < kDims; ++d) {
      lo[d] = std::min(lo[d], p[d]);
      hi[d] = std::max(hi[d], p[d]);
    }
  }
  lo_.insert(lo_.end(), lo, lo + kDims);
  hi_.insert(hi_.end(), hi, hi + kDims);
  if (end - begin <= kLeaf) return id;
  // Split the widest side (weighted as the distance weighs it) near the median, at a whole number
  // of leaves from `begin`, so that every leaf but the last holds exactly kLeaf frames.
  int split = 0;
  float widest = -1.0f;
  for (int d = 0; d < kDims; ++d) {
    const float w = (hi[d] - lo[d]) * (d < 8 ? space_.lambda_pos() : space_.lambda_vel());
    if (w > widest) widest = w, split = d;
  }
  const int mid = begin + ((end - begin) / 2 + kLeaf - 1) / kLeaf * kLeaf;
  const Eigen::MatrixXf& p = space_.projections();
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](int a, int b) { return p(split, a) < p(split, b); });
  const int left = build(begin, mid);
  const int right = build(mid, end);
  nodes_[static_cast<std::size_t>(id)].left = left;
  nodes_[static_cast<std::size_t>(id)].right = right;
  return id;
}

// Lower bound of d(l, r) for every r in the node's box; q = l's projections. The gaps are taken
// sixteen rows at a time, their squares summed in the fixed order of float_lanes.h.
float CandidateTree::box_bound(int node, const float* q) const { return box_box_bound(node, q, q); }

float CandidateTree::box_box_bound(int node, const float* other_lo, const float* other_hi) const {
  const std::size_t at = static_cast<std::size_t>(node) * kDims;
  const Sixteen lo = Sixteen::at(lo_.data() + at), hi = Sixteen::at(hi_.data() + at);
  const Sixteen olo = Sixteen::at(other_lo), ohi = Sixteen::at(other_hi);
  alignas(64) float g[kDims];
  Sixteen squares;
  for (int i = 0; i < Sixteen::kParts; ++i) {
    const Floats below = lo.part[i] - ohi.part[i], above = olo.part[i] - hi.part[i];
    Floats gap = below > above ? below : above;
    gap = gap > Floats{} ? gap : Floats{};
    squares.part[i] = gap * gap;
  }
  squares.store(g);
  return space_.lambda_pos() * std::sqrt(sum8(g)) + space_.lambda_vel() * std::sqrt(sum8(g + 8));
}

// Each lane a frame, its rows summed in order (PoseSpace::lower_bound_slots); bit i set when frame
// begin + i's bound is within the radius.
unsigned CandidateTree::leaf_within(int begin, const float* q, float radius) const {
  const float* block = blocks_.row(static_cast<std::size_t>(begin / kLeaf));
  unsigned bits = 0;
  for (int c = 0; c < kLeaf; c += kLanes) {
    Floats sp = {}, sv = {};
    for (int d = 0; d < 8; ++d) {
      const Floats g = load(block + static_cast<std::ptrdiff_t>(d * kLeaf + c)) - q[d];
      sp += g * g;
    }
    for (int d = 8; d < kDims; ++d) {
      const Floats g = load(block + static_cast<std::ptrdiff_t>(d * kLeaf + c)) - q[d];
      sv += g * g;
    }
    const Floats lb = space_.lambda_pos() * square_root(sp) + space_.lambda_vel() * square_root(sv);
    bits |= lanes_at_most(lb, radius) << c;
  }
  return bits;
}

unsigned CandidateTree::leaf_reached(int node, const float* q, const float* radii) const {
  const float* lo = lo_.data() + static_cast<std::size_t>(node) * kDims;
  const float* hi = hi_.data() + static_cast<std::size_t>(node) * kDims;
  unsigned bits = 0;
  for (int c = 0; c < kGroup; c += kLanes) {
    Floats sp = {}, sv = {};
    for (int d = 0; d < kDims; ++d) {
      const Floats x = load(q + static_cast<std::ptrdiff_t>(d * kGroup + c));
      const Floats below = lo[d] - x, above = x - hi[d];
      Floats gap = below > above ? below : above;
      gap = gap > Floats{} ? gap : Floats{};
      (d < 8 ? sp : sv) += gap * gap;
    }
    const Floats lb = space_.lambda_pos() * square_root(sp) + space_.lambda_vel() * square_root(sv);
    bits |= lanes_at_most(lb, load(radii + c)) << c;
  }
  return bits;
}

// Member r of K_l at float distance d: gathered (which, with a bound, tightens the radius once k
// are in).
void CandidateTree::take(int l, int sl, int sr, double theta, Gathered& g) const {
  const int r = order_[static_cast<std::size_t>(sr)];
  if (!allowed_(l, r)) return;
  const float d = space_.ordered_rows() ? space_.approx_slots(sl, sr) : space_.approx(l, r);
  if (d > g.radius() || !space_.within(l, r, d, theta)) return;
  g.add(d, r);
}

void CandidateTree::find(int l, CandidateScratch& s, std::vector<Candidate>& out) const {
  if (max_checks_ > 0) {
    // What find_run finds for l: the walk of l's leaf.
    const int slot = space_.slot(l), leaf = slot / kLeaf * kLeaf;
    find_run(leaf, std::min(kLeaf, frames() - leaf), s.leaf, s.leaf_found);
    out = s.leaf_found[static_cast<std::size_t>(slot - leaf)];
    return;
  }
  const double theta = theta_[static_cast<std::size_t>(l)];
  Gathered g(space_, k_, space_.radius(theta), s.items, s.kth, s.ties);
  if (g.radius() < 0) {
    out.clear();
    return;
  }
  const float* q = space_.projections().col(space_.slot(l)).data();
  descend(l, space_.slot(l), q, theta, g, s);
  g.resolve(l, out);
}

void CandidateTree::find_run(int first, int count, std::vector<CandidateScratch>& scratch,
                             std::vector<std::vector<Candidate>>& out) const {
  if (scratch.size() < static_cast<std::size_t>(kGroup)) scratch.resize(static_cast<std::size_t>(kGroup));
  if (out.size() < static_cast<std::size_t>(count)) out.resize(static_cast<std::size_t>(count));
  if (max_checks_ == 0) {
    // Searched to the end, a frame finds the same in any group: groups from `first` on.
    for (int i = 0; i < count; i += kGroup)
      find_group(first + i, std::min(count - i, kGroup), 0, scratch.data(), &out[static_cast<std::size_t>(i)]);
    return;
  }
  // The budget decides what a frame finds, so its group is always its whole leaf; a leaf the run
  // covers only in part is searched into spare lists.
  const long budget = kLeafWalkChecks * max_checks_;
  std::vector<std::vector<Candidate>> spare;
  for (int leaf = first / kLeaf * kLeaf; leaf < first + count; leaf += kLeaf) {
    const int size = std::min(kLeaf, frames() - leaf);
    if (leaf >= first && leaf + size <= first + count) {
      find_group(leaf, size, budget, scratch.data(), &out[static_cast<std::size_t>(leaf - first)]);
      continue;
    }
    spare.resize(static_cast<std::size_t>(kLeaf));
    find_group(leaf, size, budget, scratch.data(), spare.data());
    for (int s = std::max(leaf, first); s < std::min(leaf + size, first + count); ++s)
      out[static_cast<std::size_t>(s - first)].swap(spare[static_cast<std::size_t>(s - leaf)]);
  }
}

// The exact search of up to kGroup neighbouring frames (in the tree's order) together: one
// best-first walk of the tree for all of them, ordered by the bound between each node's box and the
// box of the frames, and pruned by the largest of their radii; at each leaf reached, each frame
// takes the frames within its own radius, as find does. Every leaf a frame's own search would open,
// one whose box is within the frame's final radius, has a bound no larger (box_box_bound) and is
// opened, so each frame gathers every member its own search gathers, and its K_l is the same: the
// members are decided by the final radius, which the k nearest set whatever the order they were
// taken in. The walk and the nodes' bounds are shared: they were half of a seven-minute reference's
// search, and each frame now takes a few more frames, from leaves opened for the others.
// With max_checks the walk stops once it has examined that many frames (for all of them): each
// frame then has what the leaves opened so far hold. Those are the leaves nearest the group's box,
// so a frame sees the region around it, and more: its far
// members, which a budget misses, are often nearer the other frames of the group.
void CandidateTree::find_group(int first, int count, long max_checks, CandidateScratch* scratch,
                               std::vector<Candidate>* out) const {
  struct Query {
    int l = 0, sl = 0;
    double theta = 0.0;
    const float* q = nullptr;
    std::vector<Candidate>* out = nullptr;
    std::optional<Gathered> g;  // (Gathered holds references: made in place)
  };
  Query queries[kGroup];
  int active = 0;
  float reach = -1.0f;  // the largest radius of the frames still searching
  for (int i = 0; i < count; ++i) {
    const int l = order_[static_cast<std::size_t>(first + i)];
    const double theta = theta_[static_cast<std::size_t>(l)];
    CandidateScratch& s = scratch[i];
    Query& x = queries[active];
    x.g.emplace(space_, k_, space_.radius(theta), s.items, s.kth, s.ties);
    if (x.g->radius() < 0) {
      out[i].clear();
      continue;
    }
    x.l = l;
    x.theta = theta;
    x.sl = space_.slot(l);
    x.q = space_.projections().col(x.sl).data();
    x.out = &out[i];
    reach = std::max(reach, x.g->radius());
    ++active;
  }
  // The box of the frames searching (their projections' least and greatest values).
  alignas(64) float box_lo[kDims], box_hi[kDims];
  std::fill(box_lo, box_lo + kDims, std::numeric_limits<float>::max());
  std::fill(box_hi, box_hi + kDims, std::numeric_limits<float>::lowest());
  for (int i = 0; i < active; ++i)
    for (int d = 0; d < kDims; ++d) {
      box_lo[d] = std::min(box_lo[d], queries[i].q[d]);
      box_hi[d] = std::max(box_hi[d], queries[i].q[d]);
    }
  // The frames' projections dimension by dimension, and their radii (-1 past the active frames:
  // no bound is within it), for leaf_reached.
  alignas(64) float q_by_dim[kDims * kGroup];
  alignas(64) float radii[kGroup];
  for (int i = 0; i < kGroup; ++i) {
    radii[i] = i < active ? queries[i].g->radius() : -1.0f;
    for (int d = 0; d < kDims; ++d) q_by_dim[d * kGroup + i] = i < active ? queries[i].q[d] : 0.0f;
  }
  if (active > 0) {
    long checks = 0;
    std::vector<OpenNode>& open = scratch[0].open;
    open.clear();
    auto later = [](const OpenNode& a, const OpenNode& b) { return a.bound > b.bound; };
    open.push_back({box_box_bound(0, box_lo, box_hi), 0});
    while (!open.empty()) {
      std::pop_heap(open.begin(), open.end(), later);
      const OpenNode top = open.back();
      open.pop_back();
      if (top.bound > reach) break;
      const Node* node = &nodes_[static_cast<std::size_t>(top.node)];
      while (node->left >= 0) {
        float near = box_box_bound(node->left, box_lo, box_hi), far = box_box_bound(node->right, box_lo, box_hi);
        int near_id = node->left, far_id = node->right;
        if (far < near) std::swap(near, far), std::swap(near_id, far_id);
        if (far <= reach) {
          open.push_back({far, far_id});
          std::push_heap(open.begin(), open.end(), later);
        }
        if (near > reach) break;
        node = &nodes_[static_cast<std::size_t>(near_id)];
      }
      if (node->left >= 0) continue;
      const unsigned mask = (1u << (node->end - node->begin)) - 1u;
      // Only the frames the leaf's box is within reach of look at its frames (most are not).
      const int leaf = static_cast<int>(node - nodes_.data());
      for (unsigned reached = leaf_reached(leaf, q_by_dim, radii); reached != 0; reached &= reached - 1) {
        const int i = __builtin_ctz(reached);
        Query& x = queries[i];
        for (unsigned within = leaf_within(node->begin, x.q, x.g->radius()) & mask; within != 0; within &= within - 1)
          take(x.l, x.sl, node->begin + __builtin_ctz(within), x.theta, *x.g);
        radii[i] = x.g->radius();
      }
      reach = *std::max_element(radii, radii + active);
      checks += node->end - node->begin;
      if (max_checks > 0 && checks >= max_checks) break;
    }
  }
  for (int i = 0; i < active; ++i) queries[i].g->resolve(queries[i].l, *queries[i].out);
}

// Best first: from the open node with the lowest bound down into the nearer child at every level
// (the farther one waits among the open nodes), then through the leaf reached, until no open node
// is within reach or max_checks frames were examined (0: no budget).
void CandidateTree::descend(int l, int sl, const float* q, double theta, Gathered& g, CandidateScratch& s) const {
  s.open.clear();
  // (Equal bounds leave the heap in an order fixed by the sequence of pushes: the same in every build.)
  auto later = [](const OpenNode& a, const OpenNode& b) { return a.bound > b.bound; };
  s.open.push_back({box_bound(0, q), 0});
  long checks = 0;
  while (!s.open.empty()) {
    std::pop_heap(s.open.begin(), s.open.end(), later);
    const OpenNode top = s.open.back();
    s.open.pop_back();
    if (top.bound > g.radius()) break;
    const Node* node = &nodes_[static_cast<std::size_t>(top.node)];
    while (node->left >= 0) {
      float near = box_bound(node->left, q), far = box_bound(node->right, q);
      int near_id = node->left, far_id = node->right;
      if (far < near) std::swap(near, far), std::swap(near_id, far_id);
      if (far <= g.radius()) {
        s.open.push_back({far, far_id});
        std::push_heap(s.open.begin(), s.open.end(), later);
      }
      if (near > g.radius()) break;
      node = &nodes_[static_cast<std::size_t>(near_id)];
    }
    if (node->left >= 0) continue;
    checks += node->end - node->begin;
    // The leaf's frames within reach, as bits (most are not), their rows asked for before any is read.
    const unsigned bits = leaf_within(node->begin, q, g.radius()) & ((1u << (node->end - node->begin)) - 1u);
    for (unsigned within = bits; within != 0; within &= within - 1) {
      const int sr = node->begin + __builtin_ctz(within);
      if (space_.ordered_rows())
        space_.prefetch_slot(sr);
      else
        space_.prefetch(order_[static_cast<std::size_t>(sr)]);
    }
    for (unsigned within = bits; within != 0; within &= within - 1)
      take(l, sl, node->begin + __builtin_ctz(within), theta, g);
    if (max_checks_ > 0 && checks >= max_checks_) break;
  }
}

}  // namespace gmg::neighbours
