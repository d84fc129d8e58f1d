#include "engine/metrics/behaviour.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/metrics/naturalness.h"

namespace gmg {

double foot_slide_share(const Eigen::MatrixXd& pos, double fps, const std::vector<Leg>& legs,
                        const FootSlideParams& params) {
  const Eigen::Index frames = pos.rows();
  if (legs.empty() || frames < 2) return 0.0;
  std::vector<double> floor;
  for (const Leg& leg : legs) {
    std::vector<double> y(static_cast<std::size_t>(frames));
    for (Eigen::Index t = 0; t < frames; ++t) y[static_cast<std::size_t>(t)] = pos(t, 3 * leg.ankle + 1);
    floor.push_back(percentile(y, 1.0));
  }
  long sliding = 0;
  for (Eigen::Index t = 1; t < frames; ++t) {
    bool slides = false;
    for (std::size_t l = 0; l < legs.size() && !slides; ++l) {
      const Eigen::Index c = 3 * legs[l].ankle;
      const bool low = pos(t, c + 1) <= floor[l] + params.height_cm;
      const double speed = std::hypot(pos(t, c) - pos(t - 1, c), pos(t, c + 2) - pos(t - 1, c + 2)) * fps;
      slides = low && speed > params.speed_cm_s;
    }
    sliding += slides;
  }
  return static_cast<double>(sliding) / static_cast<double>(frames - 1);
}

Stillness stillness(const Eigen::MatrixXd& pos, double fps, const std::vector<int>& joints, double speed_cm_s) {
  Stillness s;
  const Eigen::Index frames = pos.rows();
  if (frames < 2 || joints.empty()) return s;
  const Eigen::MatrixXd rel = root_relative(pos);
  std::vector<double> speed(static_cast<std::size_t>(frames), 0.0);
  for (Eigen::Index t = 1; t < frames; ++t) {
    double sum = 0.0;
    for (int j : joints) sum += (rel.block<1, 3>(t, 3 * j) - rel.block<1, 3>(t - 1, 3 * j)).norm();
    speed[static_cast<std::size_t>(t)] = sum * fps / static_cast<double>(joints.size());
  }
  speed[0] = speed[1];
  long still = 0, run = 0, longest = 0;
  for (double v : speed) {
    run = v < speed_cm_s ? run + 1 : 0;
    still += v < speed_cm_s;
    longest = std::max(longest, run);
  }
  s.share = static_cast<double>(still) / static_cast<double>(frames);
  s.longest_s = static_cast<double>(longest) / fps;
  return s;
}

namespace {

std::vector<int> joints_or_all(const std::vector<int>& joints, Eigen::Index cols) {
  if (!joints.empty()) return joints;
  std::vector<int> all;
  for (int j = 1; j < cols / 3; ++j) all.push_back(j);
  return all;
}

double frame_distance(const Eigen::MatrixXd& a, Eigen::Index ta, const Eigen::MatrixXd& b, Eigen::Index tb,
                      const std::vector<int>& joints) {
  double sum = 0.0;
  for (int j : joints)
    sum +=
        ((a.block<1, 3>(ta, 3 * j) - a.block<1, 3>(ta, 0)) - (b.block<1, 3>(tb, 3 * j) - b.block<1, 3>(tb, 0))).norm();
  return sum / static_cast<double>(joints.size());
}

}  // namespace

double motion_distance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const std::vector<int>& joints) {
  if (a.cols() != b.cols()) throw Error("motion distance: the motions have different joints");
  const std::vector<int> js = joints_or_all(joints, a.cols());
  const Eigen::Index n = std::min(a.rows(), b.rows());
  if (n == 0 || js.empty()) return 0.0;
  double sum = 0.0;
  for (Eigen::Index t = 0; t < n; ++t) sum += frame_distance(a, t, b, t, js);
  return sum / static_cast<double>(n);
}

double pose_variation(const Eigen::MatrixXd& pos, const std::vector<int>& joints) {
  const std::vector<int> js = joints_or_all(joints, pos.cols());
  const Eigen::Index n = pos.rows();
  if (n < 2 || js.empty()) return 0.0;
  double sum = 0.0;
  for (Eigen::Index t = 0; t < n; ++t) sum += frame_distance(pos, t, pos, (t + n / 2) % n, js);
  return sum / static_cast<double>(n);
}

Reuse reference_reuse(const std::vector<int>& source_frames, int reference_frames) {
  Reuse r;
  if (reference_frames <= 0) return r;
  std::vector<int> plays(static_cast<std::size_t>(reference_frames), 0);
  for (std::size_t i = 0; i < source_frames.size(); ++i) {
    const int f = source_frames[i];
    if (f < 0 || f >= reference_frames) throw Error("reference reuse: frame " + std::to_string(f) + " out of range");
    if (i == 0 || source_frames[i - 1] != f) ++plays[static_cast<std::size_t>(f)];
  }
  r.max_plays = *std::max_element(plays.begin(), plays.end());
  r.coverage = static_cast<double>(std::count_if(plays.begin(), plays.end(), [](int p) { return p > 0; })) /
               static_cast<double>(reference_frames);
  return r;
}

}  // namespace gmg
