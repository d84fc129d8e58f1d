#include "engine/blend.h"

#include <cmath>

#include "engine/error.h"

namespace gmg {

double blend_weight(int i, int n, const std::string& curve) {
  const double x = static_cast<double>(i + 1) / static_cast<double>(n + 1);
  if (curve == "linear") return x;
  auto logistic = [](double t) { return 1.0 / (1.0 + std::exp(-10.0 * (t - 0.5))); };
  const double lo = logistic(1.0 / (n + 1)), hi = logistic(static_cast<double>(n) / (n + 1));
  if (hi - lo < 1e-12) return x;
  // Rescaled so the first and last weights equal the linear curve's: same end points, an
  // ease-in/ease-out in between.
  const double first = 1.0 / (n + 1), last = static_cast<double>(n) / (n + 1);
  return first + (logistic(x) - lo) / (hi - lo) * (last - first);
}

Motion resample_path(const Motion& source, const std::vector<int>& path, int length) {
  if (path.empty() || length < 1) throw Error("resample_path: empty path or length");
  Motion out = motion_rest(source.skeleton, source.fps, length);
  const int joints = source.joint_count();
  const int n = static_cast<int>(path.size());
  for (int i = 0; i < length; ++i) {
    const double x = length == 1 ? 0.0 : static_cast<double>(i) * (n - 1) / (length - 1);
    const int a = std::min(n - 1, static_cast<int>(std::floor(x)));
    const int b = std::min(n - 1, a + 1);
    const double t = x - a;
    for (int j = 0; j < joints; ++j) {
      out.rotations[out.index(i, j)] = slerp_shortest(source.rotation(path[a], j), source.rotation(path[b], j), t);
      out.translations[out.index(i, j)] =
          (1.0 - t) * source.translation(path[a], j) + t * source.translation(path[b], j);
    }
  }
  return out;
}

Motion blend_concatenate(const std::vector<Motion>& pieces, const BlendParams& params) {
  if (pieces.empty()) throw Error("blend_concatenate: nothing to concatenate");
  int total = 0;
  for (const Motion& p : pieces) total += p.frame_count;
  Motion out = motion_rest(pieces.front().skeleton, pieces.front().fps, total);
  const int joints = out.joint_count();
  int filled = 0;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Motion& right = pieces[k];
    for (int f = 0; f < right.frame_count; ++f) motion_copy_frame(right, f, out, filled + f);
    if (k > 0 && filled > 0 && right.frame_count > 0) {
      const int ll = std::min(params.l_blend, filled);
      const int lr = std::min(params.l_blend, right.frame_count);
      const int n = ll + lr;
      const int start = filled - ll;
      // Both sequences of the cross-fade, taken before any frame is overwritten.
      std::vector<glm::dquat> a_rot(static_cast<std::size_t>(n) * joints), b_rot(a_rot.size());
      std::vector<glm::dvec3> a_tr(a_rot.size()), b_tr(a_rot.size());
      const int left_last = filled - 1;
      for (int i = 0; i < n; ++i) {
        const int fa = i < ll ? start + i : left_last;         // left, then its last frame held
        const int fb = i < ll ? filled : filled + (i - ll);    // right's first frame held, then right
        for (int j = 0; j < joints; ++j) {
          const std::size_t s = static_cast<std::size_t>(i) * joints + j;
          a_rot[s] = out.rotation(fa, j);
          a_tr[s] = out.translation(fa, j);
          b_rot[s] = out.rotation(fb, j);
          b_tr[s] = out.translation(fb, j);
        }
      }
      for (int i = 0; i < n; ++i) {
        const double w = blend_weight(i, n, params.curve);
        for (int j = 0; j < joints; ++j) {
          const std::size_t s = static_cast<std::size_t>(i) * joints + j;
          out.rotations[out.index(start + i, j)] = slerp_shortest(a_rot[s], b_rot[s], w);
          out.translations[out.index(start + i, j)] = (1.0 - w) * a_tr[s] + w * b_tr[s];
        }
      }
    }
    filled += right.frame_count;
  }
  return out;
}

}  // namespace gmg
