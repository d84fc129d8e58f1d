#include "engine/motion/spikes.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace gmg {
namespace {

// The jerk of every joint at every frame, computed in one pass with a window of four frames' root-
// relative positions, so an hour of capture needs no more memory than a few frames.
template <typename Visit>
void each_jerk(const Motion& m, const CaptureRuns& runs, const std::vector<int>& joints, const Visit& visit) {
  const int n = m.frame_count, count = m.joint_count();
  std::vector<glm::dquat> rot(static_cast<std::size_t>(count));
  std::vector<glm::dvec3> pos(static_cast<std::size_t>(count));
  std::array<std::vector<glm::dvec3>, 4> window;
  for (auto& w : window) w.resize(joints.size());
  for (int f = 0; f < n; ++f) {
    motion_world_pose(m, f, rot, pos);
    std::vector<glm::dvec3>& now = window[static_cast<std::size_t>(f % 4)];
    for (std::size_t i = 0; i < joints.size(); ++i) now[i] = pos[static_cast<std::size_t>(joints[i])] - pos[0];
    if (f > 0 && f % (1 << 16) == 0) motion_release_frames(m, f - (1 << 16), 1 << 16);
    // The third difference over f-3 .. f, placed at f-1, inside one capture run.
    if (f < 3 || runs.first(f) > f - 3) continue;
    const auto& a = window[static_cast<std::size_t>((f - 3) % 4)];
    const auto& b = window[static_cast<std::size_t>((f - 2) % 4)];
    const auto& c = window[static_cast<std::size_t>((f - 1) % 4)];
    for (std::size_t i = 0; i < joints.size(); ++i)
      visit(f - 1, i, glm::length(now[i] - 3.0 * c[i] + 3.0 * b[i] - a[i]));
  }
  motion_release_pages(m);
}

// Medians from log-spaced histograms: 8 bins per factor of two from 2^-40 to 2^24 file units per
// frame^3, a median within 9 % of the exact one, in fixed memory.
constexpr int kBinsPerOctave = 8, kLowestOctave = -40, kOctaves = 64;
int bin_of(double v) {
  if (!(v > 0.0)) return 0;
  const int b = static_cast<int>(std::floor((std::log2(v) - kLowestOctave) * kBinsPerOctave));
  return std::clamp(b, 0, kOctaves * kBinsPerOctave - 1);
}
double bin_value(int b) { return std::exp2(kLowestOctave + (b + 0.5) / kBinsPerOctave); }

}  // namespace

std::vector<std::uint8_t> jerk_spikes(const Motion& m, const CaptureRuns& runs, const std::vector<int>& joints) {
  const int n = m.frame_count;
  std::vector<std::uint8_t> out(static_cast<std::size_t>(std::max(0, n)), 0);
  if (n < 4 || joints.empty()) return out;
  std::vector<std::vector<long>> histogram(joints.size(), std::vector<long>(kOctaves * kBinsPerOctave, 0));
  std::vector<long> total(joints.size(), 0);
  each_jerk(m, runs, joints, [&](int, std::size_t i, double jerk) {
    ++histogram[i][static_cast<std::size_t>(bin_of(jerk))];
    ++total[i];
  });
  std::vector<double> limit(joints.size(), 0.0);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    long seen = 0;
    for (int b = 0; b < kOctaves * kBinsPerOctave; ++b) {
      seen += histogram[i][static_cast<std::size_t>(b)];
      if (2 * seen >= total[i]) {
        limit[i] = b > 0 ? kSpikeFactor * bin_value(b) : 0.0;  // a joint that never moves has no spikes
        break;
      }
    }
  }
  each_jerk(m, runs, joints, [&](int f, std::size_t i, double jerk) {
    if (limit[i] > 0.0 && jerk > limit[i])
      for (int g = std::max(0, f - kSpikeMargin); g <= std::min(n - 1, f + kSpikeMargin); ++g)
        out[static_cast<std::size_t>(g)] = 1;
  });
  return out;
}

}  // namespace gmg
