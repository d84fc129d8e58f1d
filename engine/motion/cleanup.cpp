#include "engine/motion/cleanup.h"

#include <cmath>

#include <Eigen/Dense>

#include "engine/core/error.h"
#include "engine/core/math.h"
#include "engine/core/strings.h"

namespace gmg {
namespace {

// Least-squares polynomial (order) through samples y at positions 0..n-1, evaluated at `at`.
Eigen::VectorXd fit_and_evaluate(const Eigen::VectorXd& y, int order, const Eigen::VectorXd& at) {
  const Eigen::Index n = y.size();
  const double centre = 0.5 * static_cast<double>(n - 1);  // centred for conditioning
  Eigen::MatrixXd a(n, order + 1);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int p = 0; p <= order; ++p) a(i, p) = std::pow(static_cast<double>(i) - centre, p);
  const Eigen::VectorXd coef = a.colPivHouseholderQr().solve(y);
  Eigen::VectorXd out(at.size());
  for (Eigen::Index i = 0; i < at.size(); ++i) {
    double v = 0.0;
    for (int p = order; p >= 0; --p) v = v * (at(i) - centre) + coef(p);
    out(i) = v;
  }
  return out;
}

}  // namespace

std::vector<double> savgol_filter(const std::vector<double>& x, int window, int order) {
  if (window % 2 == 0 || window <= order)
    throw Error("Savitzky-Golay: the window must be odd and larger than the order");
  const int n = static_cast<int>(x.size());
  if (n < window) window = n % 2 == 1 ? n : n - 1;
  if (window <= order) return x;
  const int half = window / 2;
  // Interior: the smoothing weights are the centre row of the fit's hat matrix.
  Eigen::VectorXd weights(window);
  for (int k = 0; k < window; ++k) {
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(window);
    unit(k) = 1.0;
    Eigen::VectorXd at(1);
    at(0) = half;
    weights(k) = fit_and_evaluate(unit, order, at)(0);
  }
  std::vector<double> out(x.size());
  for (int i = half; i < n - half; ++i) {
    double v = 0.0;
    for (int k = 0; k < window; ++k) v += weights(k) * x[static_cast<std::size_t>(i - half + k)];
    out[static_cast<std::size_t>(i)] = v;
  }
  // Edges: the polynomial fitted to the first and to the last window.
  Eigen::VectorXd head(window), tail(window), head_at(half), tail_at(half);
  for (int k = 0; k < window; ++k) {
    head(k) = x[static_cast<std::size_t>(k)];
    tail(k) = x[static_cast<std::size_t>(n - window + k)];
  }
  for (int k = 0; k < half; ++k) {
    head_at(k) = k;
    tail_at(k) = window - half + k;
  }
  const Eigen::VectorXd h = fit_and_evaluate(head, order, head_at);
  const Eigen::VectorXd t = fit_and_evaluate(tail, order, tail_at);
  for (int k = 0; k < half; ++k) {
    out[static_cast<std::size_t>(k)] = h(k);
    out[static_cast<std::size_t>(n - half + k)] = t(k);
  }
  return out;
}

glm::dvec3 bone_axis(const Skeleton& skeleton, int j) {
  glm::dvec3 axis(0.0);
  for (int c = j + 1; c < skeleton.joint_count(); ++c)
    if (skeleton.joints[c].parent == j) {
      axis = skeleton.joints[c].offset;
      break;
    }
  if (glm::length(axis) < 1e-12 && skeleton.joints[j].has_end_site) axis = skeleton.joints[j].end_site;
  if (glm::length(axis) < 1e-12) axis = skeleton.joints[j].offset;
  if (glm::length(axis) < 1e-12) axis = glm::dvec3(1.0, 0.0, 0.0);
  return glm::normalize(axis);
}

void motion_lock_and_smooth(Motion& m, const std::vector<std::string>& joints, int window, int order,
                            const std::string& what) {
  for (const std::string& name : joints) {
    const int j = m.skeleton.find(name);
    if (j < 0) {
      std::vector<std::string> names;
      for (const Joint& joint : m.skeleton.joints) names.push_back(joint.name);
      std::string message = what;
      message += ": clean-up joint '" + name + "' (lock_joints) is not in the skeleton" + did_you_mean(name, names);
      throw Error(message);
    }
    const glm::dvec3 axis = bone_axis(m.skeleton, j);
    std::vector<double> twist(static_cast<std::size_t>(m.frame_count));
    for (int f = 0; f < m.frame_count; ++f) {
      const glm::dquat& q = m.rotation(f, j);
      // Twist part of q about the axis: its vector part projected on the axis, with w.
      double angle = 2.0 * std::atan2(glm::dot(glm::dvec3(q.x, q.y, q.z), axis), q.w);
      if (f > 0) angle = wrap_near(angle, twist[static_cast<std::size_t>(f - 1)]);  // the filter needs it continuous
      twist[static_cast<std::size_t>(f)] = angle;
    }
    const std::vector<double> smooth = savgol_filter(twist, window, order);
    for (int f = 0; f < m.frame_count; ++f)
      m.rotations[m.index(f, j)] = glm::angleAxis(smooth[static_cast<std::size_t>(f)], axis);
  }
  if (!joints.empty()) m.euler_hints.clear();  // the rotations no longer match the file's angles
}

void cleanup_params_validate(const CleanupParams& p) {
  require_param(p.smooth_window >= 3 && p.smooth_window % 2 == 1, "smooth_window must be odd and >= 3");
  require_param(p.smooth_order >= 0 && p.smooth_order < p.smooth_window,
                "smooth_order must be >= 0 and below smooth_window");
}

}  // namespace gmg
