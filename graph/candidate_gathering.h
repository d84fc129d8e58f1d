// Gathering a frame's candidates K_l (graph/neighbours.h) as a search finds them: which pairs may
// be transitions at all, and the members kept so far under a radius that shrinks once the bound k
// is reached. Both finders (exact_finder.h, tree_finder.h) gather through it, so they agree on
// K_l exactly. Internal to graph/.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <vector>

#include "graph/pose_space.h"

namespace gmg::neighbours {

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

struct Candidate {
  float d;  // d(l, r) in single precision
  int r;
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
  void resolve(const PoseSpace& s, int l, std::vector<int>& out);

 private:
  float kth_radius(const PoseSpace& s, float kth) const { return kth + 2.02f * s.error(kth); }

  void compact(const PoseSpace& s);

  // Keeps the k nearest by (d in double, r): those clearly nearer than the k-th float distance,
  // and the best of those within float error of it, ranked in double.
  void select(const PoseSpace& s, int l);

  std::vector<Candidate> items_;
  float radius_ = -1.0f;
  std::size_t k_ = 0;
};

}  // namespace gmg::neighbours
