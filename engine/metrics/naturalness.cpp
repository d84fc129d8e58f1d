#include "engine/metrics/naturalness.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/metrics/metrics.h"

namespace gmg {

Eigen::MatrixXd root_relative(const Eigen::MatrixXd& pos) {
  Eigen::MatrixXd out = pos;
  const Eigen::MatrixXd root = pos.leftCols(3);
  for (Eigen::Index j = 0; j < pos.cols() / 3; ++j) out.middleCols(3 * j, 3) -= root;
  return out;
}

std::vector<double> frame_steps(const Eigen::MatrixXd& pos) {
  const Eigen::MatrixXd rel = root_relative(pos);
  const Eigen::Index joints = pos.cols() / 3;
  std::vector<double> steps;
  if (pos.rows() < 2) return steps;
  steps.reserve(static_cast<std::size_t>(pos.rows() - 1));
  for (Eigen::Index t = 1; t < pos.rows(); ++t) {
    double worst = 0.0;
    for (Eigen::Index j = 1; j < joints; ++j)
      worst = std::max(worst, (rel.block<1, 3>(t, 3 * j) - rel.block<1, 3>(t - 1, 3 * j)).norm());
    steps.push_back(worst);
  }
  return steps;
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) throw Error("percentile: no values");
  std::sort(values.begin(), values.end());
  const double x = std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(values.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(x));
  const std::size_t hi = std::min(values.size() - 1, lo + 1);
  return values[lo] + (x - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

double root_speed(const Eigen::MatrixXd& pos, double fps) {
  if (pos.rows() < 2) return 0.0;
  double sum = 0.0;
  for (Eigen::Index t = 1; t < pos.rows(); ++t) sum += (pos.block<1, 3>(t, 0) - pos.block<1, 3>(t - 1, 0)).norm();
  return sum / static_cast<double>(pos.rows() - 1) * fps;
}

NaturalnessReference naturalness_reference(const Eigen::MatrixXd& pos, double fps) {
  const Eigen::MatrixXd rel = root_relative(pos);
  NaturalnessReference r;
  r.jerk = metric_jerk(rel, fps);
  r.acceleration = metric_acceleration(rel, fps);
  r.root_speed = root_speed(pos, fps);
  r.step_p999 = percentile(frame_steps(pos), 99.9);
  return r;
}

Naturalness naturalness(const Eigen::MatrixXd& pos, double fps, const NaturalnessReference& reference) {
  const Eigen::MatrixXd rel = root_relative(pos);
  auto ratio = [](double a, double b) { return b > 0.0 ? a / b : 0.0; };
  Naturalness n;
  n.jerk_ratio = ratio(metric_jerk(rel, fps), reference.jerk);
  n.acc_ratio = ratio(metric_acceleration(rel, fps), reference.acceleration);
  n.root_speed_ratio = ratio(root_speed(pos, fps), reference.root_speed);
  const std::vector<double> steps = frame_steps(pos);
  const double largest = steps.empty() ? 0.0 : *std::max_element(steps.begin(), steps.end());
  n.jump_ratio = ratio(largest, reference.step_p999);
  if (!steps.empty() && reference.step_p999 > 0.0) {
    const auto above = std::count_if(steps.begin(), steps.end(), [&](double s) { return s > reference.step_p999; });
    n.step_share = static_cast<double>(above) / static_cast<double>(steps.size());
  }
  return n;
}

int source_transitions(const std::vector<int>& source_frames) {
  int n = 0;
  for (std::size_t i = 1; i < source_frames.size(); ++i) n += source_frames[i] != source_frames[i - 1] + 1;
  return n;
}

double transitions_per_second(int transitions, double duration_s) {
  return duration_s > 0.0 ? static_cast<double>(transitions) / duration_s : 0.0;
}

}  // namespace gmg
