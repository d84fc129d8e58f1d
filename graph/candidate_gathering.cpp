#include "graph/candidate_gathering.h"

#include <algorithm>
#include <limits>

namespace gmg::neighbours {

Gathered::Gathered(const PoseSpace& space, std::size_t k, float radius, std::vector<Candidate>& items,
                   std::vector<float>& kth, std::vector<std::pair<double, int>>& ties)
    : space_(space), k_(k), radius_(radius), items_(items), kth_(kth), ties_(ties) {
  items_.clear();
  kth_.clear();
}

namespace {

// The largest of a max-heap of n values replaced by d, no larger than it: d sifted down from the
// top. (The heap's values, and so its top after every step, are those of std::pop_heap then
// std::push_heap; this walks the heap once instead of three times.) heap[n] is a sentinel below
// every value, so the larger child is chosen without a branch.
void replace_top(float* heap, std::size_t n, float d) {
  std::size_t i = 0;
  for (std::size_t c = 1; c < n; c = 2 * i + 1) {
    c += static_cast<std::size_t>(heap[c + 1] > heap[c]);
    if (!(heap[c] > d)) break;
    heap[i] = heap[c];
    i = c;
  }
  heap[i] = d;
}

}  // namespace

void Gathered::add(float d, int r) {
  items_.push_back({d, r});
  if (k_ == 0) return;
  if (kth_.empty()) {
    // Until k members are in, the radius stays as it is, and the heap of the k nearest is made
    // once, from them, when the k-th arrives (items_ holds every member so far: nothing is dropped
    // before 2 k + 32). The walk finds the nearest first, so each pushed onto the heap as it came
    // rose to its top: most of the gathering's time, for frames most of which never reach k.
    if (items_.size() < k_) return;
    for (const Candidate& c : items_) kth_.push_back(c.d);
    std::make_heap(kth_.begin(), kth_.end());
    kth_.push_back(-std::numeric_limits<float>::infinity());  // replace_top's sentinel
  } else if (d < kth_.front()) {
    replace_top(kth_.data(), k_, d);
  }
  limit(kth_radius(space_, kth_.front()));
  if (items_.size() >= 2 * k_ + 32) compact();
}

// Drops the members past the radius of the k-th nearest so far (all but a few past k): the list
// stays short however many frames lie under the threshold. (Which ones are kept, not their order,
// decides K_l: resolve sorts them.)
void Gathered::compact() {
  items_.erase(std::remove_if(items_.begin(), items_.end(), [&](const Candidate& c) { return c.d > radius_; }),
               items_.end());
}

void Gathered::resolve(int l, std::vector<Candidate>& out) {
  out.clear();
  for (const Candidate& c : items_)
    if (c.d <= radius_) out.push_back(c);
  if (k_ && out.size() > k_) {
    // The k-th nearest float distance, then the members clearly nearer (first) and those within
    // float error of it (next): two partitions, not a sort, as only these sets matter (the tied
    // ones are ranked below, the result is sorted by r at the end).
    const auto nearer = [](const Candidate& a, const Candidate& b) { return a.d < b.d; };
    std::nth_element(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(k_ - 1), out.end(), nearer);
    const float kth = out[k_ - 1].d;
    const float lo = kth - 2.02f * space_.error(kth), hi = kth_radius(space_, kth);
    const auto sure_end = std::partition(out.begin(), out.end(), [&](const Candidate& c) { return c.d < lo; });
    const auto tied_end = std::partition(sure_end, out.end(), [&](const Candidate& c) { return c.d <= hi; });
    const auto sure = static_cast<std::size_t>(sure_end - out.begin());
    ties_.clear();
    for (std::size_t i = sure; i < static_cast<std::size_t>(tied_end - out.begin()); ++i)
      ties_.emplace_back(space_.exact(l, out[i].r), static_cast<int>(i));
    std::sort(ties_.begin(), ties_.end(), [&](const std::pair<double, int>& a, const std::pair<double, int>& b) {
      return a.first < b.first || (a.first == b.first && out[static_cast<std::size_t>(a.second)].r <
                                                             out[static_cast<std::size_t>(b.second)].r);
    });
    // The tied members that make it, after the sure ones.
    std::vector<Candidate> chosen;
    for (std::size_t i = 0; i < ties_.size() && sure + chosen.size() < k_; ++i)
      chosen.push_back(out[static_cast<std::size_t>(ties_[i].second)]);
    out.resize(sure);
    out.insert(out.end(), chosen.begin(), chosen.end());
  }
  std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.r < b.r; });
}

}  // namespace gmg::neighbours
