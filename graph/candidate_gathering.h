// Gathering a frame's candidates K_l (graph/neighbours.h) as the search finds them: which pairs may
// be transitions at all, and the members kept so far under a radius that shrinks once the bound k
// is reached. Internal to graph/.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <vector>

#include "graph/neighbours.h"
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

// The radius within which a member can still be among the k nearest, once the k-th nearest float
// distance is `kth`: the k-th plus the float error of two distances.
inline float kth_radius(const PoseSpace& s, float kth) { return kth + 2.02f * s.error(kth); }

// The members gathered for frame l (each with d(l, r) <= theta_l, decided exactly): keeps them
// while the search adds more, and gives K_l at the end.
class Gathered {
 public:
  // `items`, `kth` and `ties` are the caller's (a thread's scratch), cleared here; radius < 0: no
  // member.
  Gathered(const PoseSpace& space, std::size_t k, float radius, std::vector<Candidate>& items, std::vector<float>& kth,
           std::vector<std::pair<double, int>>& ties);
  float radius() const { return radius_; }

  // A member at float distance d; with a bound, the radius shrinks to the k-th nearest member's
  // (plus float error) as soon as k are in, and after every member after that: none farther can
  // belong to K_l. (A search reading the radius between members then prunes with the tightest.)
  void add(float d, int r);
  // The radius a search may use: at most the current one.
  void limit(float radius) { radius_ = radius < radius_ ? radius : radius_; }

  // K_l by ascending r: the members within the radius, and with a bound the k nearest by (d in
  // double, r): those clearly nearer than the k-th float distance, and the best of those within
  // float error of it, ranked in double. Each keeps its float distance.
  void resolve(int l, std::vector<Candidate>& out);

 private:
  void compact();

  const PoseSpace& space_;
  std::size_t k_;
  float radius_;
  std::vector<Candidate>& items_;
  // Once k members are in, the k smallest distances so far (a max-heap) and a sentinel; empty before.
  std::vector<float>& kth_;
  std::vector<std::pair<double, int>>& ties_;
};

}  // namespace gmg::neighbours
