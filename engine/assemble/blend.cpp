#include "engine/assemble/blend.h"

#include <cmath>

#include "engine/core/error.h"

namespace gmg {

double blend_weight(int i, int n, BlendCurve curve) {
  const double x = static_cast<double>(i + 1) / static_cast<double>(n + 1);
  if (curve == BlendCurve::Linear) return x;
  auto logistic = [](double t) { return 1.0 / (1.0 + std::exp(-10.0 * (t - 0.5))); };
  const double lo = logistic(1.0 / (n + 1)), hi = logistic(static_cast<double>(n) / (n + 1));
  if (hi - lo < 1e-12) return x;
  // Rescaled so the first and last weights equal the linear curve's: same end points, an
  // ease-in/ease-out in between.
  const double first = 1.0 / (n + 1), last = static_cast<double>(n) / (n + 1);
  return first + (logistic(x) - lo) / (hi - lo) * (last - first);
}

namespace {

glm::dquat quat_power(const glm::dquat& q, double t) { return slerp_shortest(glm::dquat(1.0, 0.0, 0.0, 0.0), q, t); }

// SPEC's held-frame cross-fade of the window [start, start + ll + lr) of out.
void crossfade_junction(Motion& out, int filled, int ll, int lr, const BlendParams& params) {
  const int joints = out.joint_count();
  const int n = ll + lr;
  const int start = filled - ll;
  // Both sequences of the cross-fade, taken before any frame is overwritten.
  std::vector<glm::dquat> a_rot(static_cast<std::size_t>(n) * joints), b_rot(a_rot.size());
  std::vector<glm::dvec3> a_tr(a_rot.size()), b_tr(a_rot.size());
  const int left_last = filled - 1;
  for (int i = 0; i < n; ++i) {
    const int fa = i < ll ? start + i : left_last;       // left, then its last frame held
    const int fb = i < ll ? filled : filled + (i - ll);  // right's first frame held, then right
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

// Spreads the junction's excess jump over the window (see blend.h). right_count is the number
// of right-piece frames already in out from `filled` on.
void offset_junction(Motion& out, int filled, int ll, int lr, int right_count, const BlendParams& params) {
  const int joints = out.joint_count();
  const int n = ll + lr;
  const int start = filled - ll;
  const int left_last = filled - 1, right_first = filled;
  const bool has_left_prev = left_last - 1 >= 0;
  const bool has_right_next = right_count >= 2;
  std::vector<double> w(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) w[static_cast<std::size_t>(k)] = blend_weight(k, n, params.curve);
  for (int j = 0; j < joints; ++j) {
    // Boundary velocities (as deltas applied on the left) and their mean.
    const glm::dquat identity(1.0, 0.0, 0.0, 0.0);
    const glm::dquat dl =
        has_left_prev ? out.rotation(left_last, j) * glm::conjugate(out.rotation(left_last - 1, j)) : identity;
    const glm::dquat dr =
        has_right_next ? out.rotation(right_first + 1, j) * glm::conjugate(out.rotation(right_first, j)) : identity;
    const glm::dquat step = slerp_shortest(has_left_prev ? dl : dr, has_right_next ? dr : dl, 0.5);
    const glm::dquat predicted = step * out.rotation(left_last, j);
    glm::dquat excess = glm::normalize(out.rotation(right_first, j) * glm::conjugate(predicted));
    if (excess.w < 0.0) excess = -excess;

    const glm::dvec3 vl =
        has_left_prev ? out.translation(left_last, j) - out.translation(left_last - 1, j) : glm::dvec3(0.0);
    const glm::dvec3 vr =
        has_right_next ? out.translation(right_first + 1, j) - out.translation(right_first, j) : glm::dvec3(0.0);
    const glm::dvec3 mean_step = has_left_prev && has_right_next ? 0.5 * (vl + vr) : (has_left_prev ? vl : vr);
    const glm::dvec3 excess_t = out.translation(right_first, j) - (out.translation(left_last, j) + mean_step);

    for (int k = 0; k < n; ++k) {
      const int f = start + k;
      const double wk = w[static_cast<std::size_t>(k)];
      glm::dquat& q = out.rotations[out.index(f, j)];
      glm::dvec3& t = out.translations[out.index(f, j)];
      if (k < ll) {
        q = glm::normalize(quat_power(excess, wk) * q);
        t += wk * excess_t;
      } else {
        q = glm::normalize(quat_power(glm::conjugate(excess), 1.0 - wk) * q);
        t -= (1.0 - wk) * excess_t;
      }
    }
  }
}

}  // namespace

Motion blend_concatenate(const std::vector<Motion>& pieces, const BlendParams& params) {
  if (pieces.empty()) throw Error("blend_concatenate: nothing to concatenate");
  int total = 0;
  for (const Motion& p : pieces) total += p.frame_count;
  Motion out = motion_rest(pieces.front().skeleton, pieces.front().fps, total);
  int filled = 0;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Motion& right = pieces[k];
    for (int f = 0; f < right.frame_count; ++f) motion_copy_frame(right, f, out, filled + f);
    if (k > 0 && filled > 0 && right.frame_count > 0 && params.l_blend > 0) {
      const int ll = std::min(params.l_blend, filled);
      const int lr = std::min(params.l_blend, right.frame_count);
      if (params.mode == BlendMode::Crossfade)
        crossfade_junction(out, filled, ll, lr, params);
      else
        offset_junction(out, filled, ll, lr, right.frame_count, params);
    }
    filled += right.frame_count;
  }
  return out;
}

}  // namespace gmg
