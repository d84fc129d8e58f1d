#include "engine/metrics/behaviour.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace gmg {
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

}  // namespace gmg
