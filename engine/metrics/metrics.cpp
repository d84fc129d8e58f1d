// Objective gesture metrics; formulas, units and constants are documented in metrics.h.
#include "engine/metrics/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>  // cross product

#include "engine/core/error.h"
#include "engine/core/math.h"

namespace gmg {
namespace {

std::string shape_text(const Eigen::MatrixXd& m) {
  return std::to_string(m.rows()) + " frames x " + std::to_string(m.cols() / 3) + " joints (" +
         std::to_string(m.cols()) + " columns)";
}

// Checks what every metric assumes of a position matrix and returns its joint count.
int check_positions(const char* fn, const char* what, const Eigen::MatrixXd& pos, double fps, Eigen::Index min_frames) {
  if (!(std::isfinite(fps) && fps > 0.0))
    throw Error(std::string(fn) + ": fps must be finite and > 0, got " + std::to_string(fps));
  if (pos.cols() == 0 || pos.cols() % 3 != 0)
    throw Error(std::string(fn) + ": " + what + " has " + std::to_string(pos.cols()) +
                " columns; expected 3 per joint (x, y, z) and at least one joint");
  if (pos.rows() < min_frames)
    throw Error(std::string(fn) + ": " + what + " needs at least " + std::to_string(min_frames) + " frames, got " +
                std::to_string(pos.rows()));
  if (!pos.allFinite()) {
    for (Eigen::Index r = 0; r < pos.rows(); ++r)
      for (Eigen::Index c = 0; c < pos.cols(); ++c)
        if (!std::isfinite(pos(r, c)))
          throw Error(std::string(fn) + ": " + what + " has a non-finite value at frame " + std::to_string(r) +
                      ", joint " + std::to_string(c / 3) + ", axis " + "xyz"[c % 3]);
  }
  return static_cast<int>(pos.cols() / 3);
}

void check_params(const char* fn, const MetricParams& p) {
  auto bad = [fn](const std::string& what) { throw Error(std::string(fn) + ": " + what); };
  if (!(std::isfinite(p.bc_sigma_s) && p.bc_sigma_s > 0.0)) bad("bc_sigma_s must be > 0");
  if (p.smooth_window < 0) bad("smooth_window must be >= 0");
  if (!(p.div_angle_deg > 0.0 && p.div_angle_deg < 180.0)) bad("div_angle_deg must be in (0, 180)");
  if (!(std::isfinite(p.div_min_speed_frac) && p.div_min_speed_frac >= 0.0)) bad("div_min_speed_frac must be >= 0");
  if (!(std::isfinite(p.hist_bin_width) && p.hist_bin_width > 0.0)) bad("hist_bin_width must be > 0");
  if (p.hist_bin_count < 1 || p.hist_bin_count > 100000) bad("hist_bin_count must be in [1, 100000]");
  // Genea bins cover [0, 49]: a width below 49 / 100000 would allocate an absurd histogram.
  if (p.hist_bins == HistogramBins::Genea && p.hist_bin_width < 49.0 / 100000) bad("hist_bin_width must be >= 0.00049");
}

// |p(t, j) - p(t-1, j)| * fps for t = 1..T-1: rows T-1, one column per joint.
Eigen::MatrixXd backward_speeds(const Eigen::MatrixXd& pos, double fps) {
  const Eigen::Index n = pos.rows() - 1, joints = pos.cols() / 3;
  Eigen::MatrixXd s(n, joints);
  for (Eigen::Index t = 0; t < n; ++t)
    for (Eigen::Index j = 0; j < joints; ++j)
      s(t, j) = (pos.block<1, 3>(t + 1, 3 * j) - pos.block<1, 3>(t, 3 * j)).norm() * fps;
  return s;
}

// Mean over frames and joints of the norm of the k-th forward difference, times fps^k.
// Binomial coefficients with alternating sign give the k-th difference exactly.
double mean_difference_norm(const Eigen::MatrixXd& pos, double fps, int k) {
  static const double kCoeffs[2][4] = {{1, -2, 1, 0}, {-1, 3, -3, 1}};
  const double* c = kCoeffs[k - 2];
  const Eigen::Index n = pos.rows() - k, joints = pos.cols() / 3;
  double sum = 0.0;
  for (Eigen::Index t = 0; t < n; ++t)
    for (Eigen::Index j = 0; j < joints; ++j) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      for (int i = 0; i <= k; ++i) d += c[i] * pos.block<1, 3>(t + i, 3 * j).transpose();
      sum += d.norm();
    }
  return sum / static_cast<double>(n * joints) * std::pow(fps, k);
}

// Centred moving average, window shrunk (and kept centred) at the ends.
std::vector<double> smooth(const std::vector<double>& x, int window) {
  const int half = window / 2, n = static_cast<int>(x.size());
  if (half == 0) return x;
  std::vector<double> y(x.size());
  for (int i = 0; i < n; ++i) {
    const int h = std::min({half, i, n - 1 - i});
    double sum = 0.0;
    for (int k = i - h; k <= i + h; ++k) sum += x[static_cast<std::size_t>(k)];
    y[static_cast<std::size_t>(i)] = sum / (2 * h + 1);
  }
  return y;
}

}  // namespace

double metric_syn(const Eigen::MatrixXd& gen, const Eigen::MatrixXd& truth, double fps) {
  check_positions("metric_syn", "generated motion", gen, fps, 2);
  check_positions("metric_syn", "ground-truth motion", truth, fps, 2);
  if (gen.rows() != truth.rows() || gen.cols() != truth.cols())
    throw Error("metric_syn: shapes differ: generated " + shape_text(gen) + ", ground truth " + shape_text(truth));
  return (backward_speeds(gen, fps) - backward_speeds(truth, fps)).cwiseAbs().mean();
}

std::vector<double> motion_beats(const Eigen::MatrixXd& pos, double fps, const MetricParams& params) {
  check_params("motion_beats", params);
  const int joints = check_positions("motion_beats", "motion", pos, fps, 3);

  // s[i] belongs to frame i + 1.
  const Eigen::Index n = pos.rows() - 2;
  std::vector<double> s(static_cast<std::size_t>(n));
  for (Eigen::Index t = 1; t <= n; ++t) {
    double sum = 0.0;
    for (Eigen::Index j = 0; j < joints; ++j)
      sum += (pos.block<1, 3>(t + 1, 3 * j) - pos.block<1, 3>(t - 1, 3 * j)).norm();
    s[static_cast<std::size_t>(t - 1)] = sum / joints * fps / 2.0;
  }
  s = smooth(s, params.smooth_window);

  std::vector<double> beats;
  const std::size_t m = s.size();
  for (std::size_t i = 1; i + 1 < m; ++i) {
    if (!(s[i] < s[i - 1])) continue;
    std::size_t last = i;  // end of a run of equal values (a held pose)
    while (last + 1 < m && s[last + 1] == s[i]) ++last;
    if (last + 1 >= m) break;  // the run reaches the end: not a minimum
    if (s[last + 1] > s[i]) {
      double frame = 0.5 * static_cast<double>(i + last);
      if (last == i) {
        const double curv = s[i - 1] - 2.0 * s[i] + s[i + 1];  // > 0 at a strict minimum
        frame += std::clamp(0.5 * (s[i - 1] - s[i + 1]) / curv, -0.5, 0.5);
      }
      beats.push_back((frame + 1.0) / fps);
    }
    i = last;
  }
  return beats;
}

double metric_bc(const Eigen::MatrixXd& pos, double fps, const std::vector<double>& audio_beats_s,
                 const MetricParams& params) {
  for (std::size_t i = 0; i < audio_beats_s.size(); ++i)
    if (!std::isfinite(audio_beats_s[i]))
      throw Error("metric_bc: audio beat " + std::to_string(i) + " is not a finite time");
  const std::vector<double> mb = motion_beats(pos, fps, params);
  if (audio_beats_s.empty() || mb.empty()) return 0.0;
  const double two_sigma2 = 2.0 * params.bc_sigma_s * params.bc_sigma_s;
  double sum = 0.0;
  for (double b : audio_beats_s) {
    // mb is ascending: the nearest beat is at the insertion point or just before it.
    const auto it = std::lower_bound(mb.begin(), mb.end(), b);
    double d = std::numeric_limits<double>::infinity();
    if (it != mb.end()) d = *it - b;
    if (it != mb.begin()) d = std::min(d, b - *(it - 1));
    sum += std::exp(-d * d / two_sigma2);
  }
  return sum / static_cast<double>(audio_beats_s.size());
}

double metric_div(const Eigen::MatrixXd& pos, double fps, const MetricParams& params) {
  check_params("metric_div", params);
  const int joints = check_positions("metric_div", "motion", pos, fps, 3);
  const Eigen::Index n = pos.rows() - 1;  // velocities v(1..T-1), stored at 0..n-1
  Eigen::MatrixXd vel(n, 3 * joints);
  for (Eigen::Index t = 0; t < n; ++t) vel.row(t) = (pos.row(t + 1) - pos.row(t)) * fps;
  const Eigen::MatrixXd speed = backward_speeds(pos, fps);
  const double min_speed = std::max(1e-12, params.div_min_speed_frac * speed.mean());
  const double threshold = params.div_angle_deg * kPi / 180.0;

  long counted = 0, large = 0;
  for (Eigen::Index t = 0; t + 1 < n; ++t)
    for (Eigen::Index j = 0; j < joints; ++j) {
      if (speed(t, j) < min_speed || speed(t + 1, j) < min_speed) continue;
      const Eigen::Vector3d a = vel.block<1, 3>(t, 3 * j).transpose();
      const Eigen::Vector3d b = vel.block<1, 3>(t + 1, 3 * j).transpose();
      // atan2 of |a x b| and a . b stays accurate near 0 and 180 deg, unlike acos.
      const double angle = std::atan2(a.cross(b).norm(), a.dot(b));
      ++counted;
      if (angle > threshold) ++large;
    }
  return counted == 0 ? 0.0 : static_cast<double>(large) / static_cast<double>(counted);
}

double metric_jerk(const Eigen::MatrixXd& pos, double fps) {
  check_positions("metric_jerk", "motion", pos, fps, 4);
  return mean_difference_norm(pos, fps, 3);
}

double metric_acceleration(const Eigen::MatrixXd& pos, double fps) {
  check_positions("metric_acceleration", "motion", pos, fps, 3);
  return mean_difference_norm(pos, fps, 2);
}

double metric_hellinger_speed(const Eigen::MatrixXd& gen, const Eigen::MatrixXd& truth, double fps,
                              const std::vector<int>& joints, const MetricParams& params) {
  check_params("metric_hellinger_speed", params);
  const int jg = check_positions("metric_hellinger_speed", "generated motion", gen, fps, 2);
  const int jt = check_positions("metric_hellinger_speed", "ground-truth motion", truth, fps, 2);
  if (jg != jt)
    throw Error("metric_hellinger_speed: joint counts differ: generated " + shape_text(gen) + ", ground truth " +
                shape_text(truth));
  std::vector<int> selected = joints;
  if (selected.empty())
    for (int j = 0; j < jg; ++j) selected.push_back(j);
  for (int j : selected)
    if (j < 0 || j >= jg)
      throw Error("metric_hellinger_speed: joint index " + std::to_string(j) + " is out of range [0, " +
                  std::to_string(jg) + ")");

  // Bin edges: Overflow adds a last bin for everything faster; Genea uses numpy's
  // arange(0, 49 + w, w) as edges, a closed last bin, and drops what lies beyond.
  const bool genea = params.hist_bins == HistogramBins::Genea;
  const double w = params.hist_bin_width;
  const std::size_t genea_edges = static_cast<std::size_t>(std::ceil((49.0 + w) / w - 1e-12));
  const std::size_t bins = genea ? genea_edges - 1 : static_cast<std::size_t>(params.hist_bin_count) + 1;
  const double genea_top = static_cast<double>(genea_edges - 1) * w;
  auto histogram = [&](const Eigen::MatrixXd& pos) {
    const Eigen::MatrixXd speed = backward_speeds(pos, fps);
    std::vector<double> h(bins, 0.0);
    double total = 0.0;
    for (int j : selected)
      for (Eigen::Index t = 0; t < speed.rows(); ++t) {
        const double v = speed(t, j);
        const double k = std::floor(v / w);
        if (genea) {
          if (v > genea_top) continue;
          h[std::min(bins - 1, static_cast<std::size_t>(k))] += 1.0;  // v == top falls in the last bin
        } else {
          h[k >= static_cast<double>(bins - 1) ? bins - 1 : static_cast<std::size_t>(k)] += 1.0;
        }
        total += 1.0;
      }
    if (total > 0.0)
      for (double& x : h) x /= total;
    return std::make_pair(h, total > 0.0);
  };
  const auto [p, p_any] = histogram(gen);
  const auto [q, q_any] = histogram(truth);
  if (!p_any || !q_any) return p_any == q_any ? 0.0 : 1.0;
  // 1 - sum sqrt(p q) = sum (sqrt p - sqrt q)^2 / 2 when both sum to 1; this form is exactly 0
  // for identical histograms, where 1 - sum would leave ~1e-16 of rounding (H ~ 1e-8).
  double h2 = 0.0;
  for (std::size_t i = 0; i < bins; ++i) {
    const double d = std::sqrt(p[i]) - std::sqrt(q[i]);
    h2 += 0.5 * d * d;
  }
  return std::sqrt(std::min(1.0, h2));
}

}  // namespace gmg
