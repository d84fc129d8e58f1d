// Lifelike metrics of a motion; definitions in lifelike.h.
#include "engine/metrics/lifelike.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>  // cross product

#include "engine/core/error.h"
#include "engine/core/math.h"
#include "engine/core/strings.h"
#include "engine/metrics/naturalness.h"

namespace gmg {
namespace {

bool holds_any(const std::string& lower_name, std::initializer_list<const char*> parts) {
  for (const char* p : parts)
    if (lower_name.find(p) != std::string::npos) return true;
  return false;
}

Eigen::Vector3d joint_at(const Eigen::MatrixXd& pos, Eigen::Index t, int j) {
  return pos.block<1, 3>(t, 3 * j).transpose();
}

double ratio_or_undefined(double a, double b) { return b > 0.0 ? a / b : LifelikeMotion::kUndefined; }

// A value must clear a reference percentile by this much to count as beyond it. A capture's legs
// often hold one pose for many frames, so the percentile equals many bends (or speeds) exactly,
// and rounding (the same rotations read from BVH text or from an .npz) would otherwise flip those
// ties; nothing physical is this close to a threshold.
constexpr double kKneeTieDeg = 1e-6;
constexpr double kSpeedTieCmS = 1e-6;

}  // namespace

void check_lifelike_params(const LifelikeParams& p) {
  auto percentile_in_range = [](const char* name, double v) {
    if (!(v > 0.0 && v < 100.0))
      throw Error(std::string("lifelike metrics: ") + name + " must be in (0, 100), got " + std::to_string(v));
  };
  auto positive = [](const char* name, double v) {
    if (!(std::isfinite(v) && v > 0.0))
      throw Error(std::string("lifelike metrics: ") + name + " must be > 0, got " + std::to_string(v));
  };
  percentile_in_range("knee_percentile", p.knee_percentile);
  percentile_in_range("jerk_percentile", p.jerk_percentile);
  percentile_in_range("still_percentile", p.still_percentile);
  percentile_in_range("foot_low_percentile", p.foot_low_percentile);
  positive("foot_height_cm", p.foot_height_cm);
  positive("foot_speed_cm_s", p.foot_speed_cm_s);
  positive("back_jump_window_s", p.back_jump_window_s);
}

LifelikeJoints lifelike_joints(const Skeleton& s) {
  const int n = s.joint_count();
  std::vector<std::vector<int>> children(static_cast<std::size_t>(n));
  for (int j = 1; j < n; ++j) {
    const int p = s.joints[static_cast<std::size_t>(j)].parent;
    if (p >= 0) children[static_cast<std::size_t>(p)].push_back(j);
  }
  // Joints are in depth-first order (parents first), so subtree sizes add up from the end.
  std::vector<int> subtree(static_cast<std::size_t>(n), 1);
  for (int j = n - 1; j > 0; --j) {
    const int p = s.joints[static_cast<std::size_t>(j)].parent;
    if (p >= 0) subtree[static_cast<std::size_t>(p)] += subtree[static_cast<std::size_t>(j)];
  }
  LifelikeJoints out;
  for (int j = 0; j < n; ++j) {
    const std::string name = ascii_lower(s.joints[static_cast<std::size_t>(j)].name);
    const std::vector<int>& kids = children[static_cast<std::size_t>(j)];
    const bool knee =
        name.find("knee") != std::string::npos || (ends_with_ci(name, "leg") && !ends_with_ci(name, "upleg"));
    const int parent = s.joints[static_cast<std::size_t>(j)].parent;
    if (knee && parent >= 0 && !kids.empty()) {
      int child = kids.front();
      for (int k : kids)
        if (subtree[static_cast<std::size_t>(k)] > subtree[static_cast<std::size_t>(child)]) child = k;
      out.knees.push_back({parent, j, child});
    }
    if (j > 0 && !kids.empty() &&
        !holds_any(name, {"thumb", "index", "middle", "ring", "pinky", "finger", "eye", "jaw"}))
      out.body.push_back(j);
    if (holds_any(name, {"ankle", "foot"}) && !holds_any(name, {"toe", "end"})) out.feet.push_back(j);
  }
  return out;
}

double bend_angle_deg(const Eigen::Vector3d& parent, const Eigen::Vector3d& joint, const Eigen::Vector3d& child) {
  const Eigen::Vector3d u = joint - parent, v = child - joint;
  // The angle between the bones' directions: atan2 stays accurate near 0 and 180 degrees.
  return std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / kPi;
}

int longest_run_below(const std::vector<double>& values, double threshold) {
  int run = 0, longest = 0;
  for (double v : values) {
    run = v < threshold ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return longest;
}

LifelikeFacts lifelike_facts(const Eigen::MatrixXd& pos, double fps, const LifelikeJoints& joints,
                             const LifelikeParams& params) {
  check_lifelike_params(params);
  if (!(std::isfinite(fps) && fps > 0.0)) throw Error("lifelike metrics: fps must be > 0");
  LifelikeFacts f;
  f.fps = fps;
  const Eigen::Index frames = pos.rows();
  auto check = [&](int j) {
    if (j < 0 || 3 * static_cast<Eigen::Index>(j) + 2 >= pos.cols())
      throw Error("lifelike metrics: joint " + std::to_string(j) + " is out of range of " +
                  std::to_string(pos.cols() / 3) + " joints");
  };
  for (const int j : joints.body) check(j);
  for (const int j : joints.feet) check(j);
  for (const KneeJoint& k : joints.knees)
    for (const int j : {k.parent, k.knee, k.child}) check(j);

  if (!joints.knees.empty()) {
    f.knee_bend_deg.assign(static_cast<std::size_t>(frames), 0.0);
    for (Eigen::Index t = 0; t < frames; ++t)
      for (const KneeJoint& k : joints.knees)
        f.knee_bend_deg[static_cast<std::size_t>(t)] =
            std::max(f.knee_bend_deg[static_cast<std::size_t>(t)],
                     bend_angle_deg(joint_at(pos, t, k.parent), joint_at(pos, t, k.knee), joint_at(pos, t, k.child)));
  }

  const Eigen::MatrixXd rel = root_relative(pos);
  const double fps3 = fps * fps * fps;
  for (Eigen::Index t = 0; t + 3 < frames; ++t) {
    double largest = 0.0;
    for (const int j : joints.body) {
      const double jerk = (joint_at(rel, t + 3, j) - 3.0 * joint_at(rel, t + 2, j) + 3.0 * joint_at(rel, t + 1, j) -
                           joint_at(rel, t, j))
                              .norm() *
                          fps3;
      f.jerk_sum += jerk;
      ++f.jerk_count;
      largest = std::max(largest, jerk);
    }
    if (!joints.body.empty()) f.jerk_frame_max.push_back(largest);
  }
  for (Eigen::Index t = 1; t < frames && !joints.body.empty(); ++t) {
    double largest = 0.0;
    for (const int j : joints.body) largest = std::max(largest, (joint_at(rel, t, j) - joint_at(rel, t - 1, j)).norm());
    f.speed_frame_max.push_back(largest * fps);
  }

  f.has_feet = !joints.feet.empty();
  if (f.has_feet && frames >= 2) {
    std::vector<char> slides(static_cast<std::size_t>(frames), 0);
    for (const int foot : joints.feet) {
      std::vector<double> height(static_cast<std::size_t>(frames));
      for (Eigen::Index t = 0; t < frames; ++t) height[static_cast<std::size_t>(t)] = pos(t, 3 * foot + 1);
      const double low = percentile(height, params.foot_low_percentile);
      for (Eigen::Index t = 1; t < frames; ++t) {
        const double horizontal =
            std::hypot(pos(t, 3 * foot) - pos(t - 1, 3 * foot), pos(t, 3 * foot + 2) - pos(t - 1, 3 * foot + 2)) * fps;
        if (height[static_cast<std::size_t>(t)] <= low + params.foot_height_cm && horizontal > params.foot_speed_cm_s)
          slides[static_cast<std::size_t>(t)] = 1;
      }
    }
    f.slide_frames = static_cast<long>(std::count(slides.begin(), slides.end(), 1));
    f.slide_of = static_cast<long>(frames - 1);
  }
  return f;
}

LifelikeReference lifelike_reference(const std::vector<LifelikeFacts>& clips, const LifelikeParams& params) {
  check_lifelike_params(params);
  LifelikeReference r;
  std::vector<double> knee, jerk_max, speed_max;
  long jerk_count = 0, slide_frames = 0, slide_of = 0;
  bool feet = false;
  for (const LifelikeFacts& c : clips) {
    r.fps = c.fps;
    knee.insert(knee.end(), c.knee_bend_deg.begin(), c.knee_bend_deg.end());
    jerk_max.insert(jerk_max.end(), c.jerk_frame_max.begin(), c.jerk_frame_max.end());
    speed_max.insert(speed_max.end(), c.speed_frame_max.begin(), c.speed_frame_max.end());
    r.jerk_mean += c.jerk_sum;
    jerk_count += c.jerk_count;
    slide_frames += c.slide_frames;
    slide_of += c.slide_of;
    feet = feet || c.has_feet;
  }
  if (jerk_max.empty())
    throw Error("lifelike metrics: the reference has no clip of 4 frames or more with body joints (jerk needs 4)");
  if (!knee.empty()) r.knee_p90_deg = percentile(knee, params.knee_percentile);
  r.jerk_mean /= static_cast<double>(jerk_count);
  r.jerk_p99 = percentile(jerk_max, params.jerk_percentile);
  r.still_speed_cm_s = percentile(speed_max, params.still_percentile);
  for (const LifelikeFacts& c : clips)
    r.still_longest_frames =
        std::max(r.still_longest_frames, longest_run_below(c.speed_frame_max, r.still_speed_cm_s - kSpeedTieCmS));
  if (feet && slide_of > 0) r.foot_slide_share = static_cast<double>(slide_frames) / static_cast<double>(slide_of);
  return r;
}

LifelikeMotion lifelike_motion(const LifelikeFacts& m, const LifelikeReference& r, const LifelikeParams& params) {
  check_lifelike_params(params);
  LifelikeMotion s;
  if (!m.knee_bend_deg.empty() && std::isfinite(r.knee_p90_deg)) {
    const auto bent = std::count_if(m.knee_bend_deg.begin(), m.knee_bend_deg.end(),
                                    [&](double b) { return b > r.knee_p90_deg + kKneeTieDeg; });
    const double share = static_cast<double>(bent) / static_cast<double>(m.knee_bend_deg.size());
    s.knee_share_ratio = share / ((100.0 - params.knee_percentile) / 100.0);
    s.knee_p90_deg = percentile(m.knee_bend_deg, params.knee_percentile);
    s.reference_knee_p90_deg = r.knee_p90_deg;
  }
  if (m.jerk_count > 0) {
    s.body_jerk_ratio = ratio_or_undefined(m.jerk_sum / static_cast<double>(m.jerk_count), r.jerk_mean);
    s.body_jerk_p99_ratio = ratio_or_undefined(percentile(m.jerk_frame_max, params.jerk_percentile), r.jerk_p99);
  }
  if (!m.speed_frame_max.empty()) {
    const int longest = longest_run_below(m.speed_frame_max, r.still_speed_cm_s - kSpeedTieCmS);
    s.still_longest_ratio = ratio_or_undefined(longest, r.still_longest_frames);
    s.still_longest_s = longest / m.fps;
    s.reference_still_longest_s = r.still_longest_frames / r.fps;
  }
  if (m.has_feet && m.slide_of > 0 && std::isfinite(r.foot_slide_share)) {
    s.foot_slide_share = static_cast<double>(m.slide_frames) / static_cast<double>(m.slide_of);
    s.reference_foot_slide_share = r.foot_slide_share;
    s.foot_slide_ratio = ratio_or_undefined(s.foot_slide_share, r.foot_slide_share);
  }
  return s;
}

}  // namespace gmg
