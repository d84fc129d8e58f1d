#include "graph/candidate_gathering.h"

#include <utility>

namespace gmg::neighbours {

void Gathered::resolve(const PoseSpace& s, int l, std::vector<int>& out) {
  out.clear();
  if (k_ && items_.size() > k_) select(s, l);
  for (const Candidate& c : items_) out.push_back(c.r);
  std::sort(out.begin(), out.end());
}

void Gathered::compact(const PoseSpace& s) {
  std::nth_element(items_.begin(), items_.begin() + static_cast<std::ptrdiff_t>(k_ - 1), items_.end(),
                   [](const Candidate& a, const Candidate& b) { return a.d < b.d; });
  radius_ = std::min(radius_, kth_radius(s, items_[k_ - 1].d));
  items_.erase(std::remove_if(items_.begin(), items_.end(), [&](const Candidate& c) { return c.d > radius_; }),
               items_.end());
}

void Gathered::select(const PoseSpace& s, int l) {
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

}  // namespace gmg::neighbours
