#include "graph/breaks.h"

#include <algorithm>

namespace gmg {

std::vector<int> capture_jump_frames(const PoseFeatures& f, const GraphParams& params) {
  return capture_jump_frames(f.positions, params);
}

std::vector<int> capture_jump_frames(const Eigen::Ref<const Eigen::MatrixXd>& positions, const GraphParams& params) {
  const int n = static_cast<int>(positions.cols());
  std::vector<int> out;
  if (n < 3) return out;
  std::vector<double> d(static_cast<std::size_t>(n - 1));
  // Positions only: a teleport also spikes the velocity term at the next frame, which would
  // mark two breaks for one jump.
  for (int i = 0; i + 1 < n; ++i) d[static_cast<std::size_t>(i)] = (positions.col(i) - positions.col(i + 1)).norm();
  std::vector<double> sorted = d;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  if (median <= 0.0) return out;  // a frozen clip has no jumps to speak of
  for (int i = 0; i + 1 < n; ++i)
    if (d[static_cast<std::size_t>(i)] > params.break_jump_factor * median) out.push_back(i);
  return out;
}

}  // namespace gmg
