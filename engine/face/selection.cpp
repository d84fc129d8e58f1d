#include "engine/face/selection.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/error.h"

namespace gmg {

double face_join_cost(const ReferenceFace& r, const FaceCandidate& a, const FaceCandidate& b,
                      const FaceParams& params) {
  if (a.clip == b.clip && std::abs(a.end - b.start) < 0.5) return 0.0;  // the reference goes on
  const int lo = r.clip_first[static_cast<std::size_t>(a.clip)], hi = r.clip_end[static_cast<std::size_t>(a.clip)] - 1;
  const int blo = r.clip_first[static_cast<std::size_t>(b.clip)],
            bhi = r.clip_end[static_cast<std::size_t>(b.clip)] - 1;
  // The last frame a plays and the first b plays (engine/face/warp.h).
  const int fa = std::clamp(static_cast<int>(std::ceil(a.end)) - 1, lo, hi);
  const int fb = std::clamp(static_cast<int>(std::ceil(b.start)), blo, bhi);
  const double distance = r.face_dims > 0 ? r.face_distance(fa, fb) : 0.0;
  return params.join_weight * (distance + params.join_cost);
}

std::vector<int> select_face_stretches(const ReferenceFace& r,
                                       const std::vector<std::vector<FaceCandidate>>& candidates,
                                       const FaceParams& params) {
  const std::size_t n = candidates.size();
  std::vector<int> out(n, 0);
  if (n == 0) return out;
  for (const auto& c : candidates)
    if (c.empty()) throw Error("face track: a unit of the new speech has no reference stretch");
  std::vector<std::vector<double>> cost(n);
  std::vector<std::vector<int>> back(n);
  cost[0].resize(candidates[0].size());
  back[0].assign(candidates[0].size(), -1);
  for (std::size_t j = 0; j < candidates[0].size(); ++j) cost[0][j] = candidates[0][j].cost;
  for (std::size_t u = 1; u < n; ++u) {
    const auto& prev = candidates[u - 1];
    const auto& here = candidates[u];
    cost[u].assign(here.size(), std::numeric_limits<double>::infinity());
    back[u].assign(here.size(), 0);
    for (std::size_t j = 0; j < here.size(); ++j) {
      for (std::size_t i = 0; i < prev.size(); ++i) {
        const double c = cost[u - 1][i] + face_join_cost(r, prev[i], here[j], params);
        if (c < cost[u][j]) {
          cost[u][j] = c;
          back[u][j] = static_cast<int>(i);
        }
      }
      cost[u][j] += here[j].cost;
    }
  }
  const auto& last = cost[n - 1];
  int best = static_cast<int>(std::min_element(last.begin(), last.end()) - last.begin());
  for (std::size_t u = n; u-- > 0;) {
    out[u] = best;
    best = back[u][static_cast<std::size_t>(best)];
  }
  return out;
}

}  // namespace gmg
