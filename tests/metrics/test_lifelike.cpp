// Lifelike metrics on small synthetic motions whose values are worked out by hand here.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/metrics/lifelike.h"

namespace gmg {
namespace {

Skeleton skeleton_of(const std::vector<std::pair<std::string, int>>& joints) {
  Skeleton s;
  for (const auto& [name, parent] : joints) {
    Joint j;
    j.name = name;
    j.parent = parent;
    s.joints.push_back(j);
  }
  return s;
}

TEST(Lifelike, JointsByNameAndHierarchy) {
  // A ZEGGS-like right leg (RightLeg has two children: the foot chain and a leaf RightLegEnd), an
  // SMPL-X-like left leg, a head with a jaw and an eye, a hand with one finger.
  const Skeleton s = skeleton_of({{"Hips", -1},
                                  {"RightUpLeg", 0},
                                  {"RightLeg", 1},
                                  {"RightLegEnd", 2},
                                  {"RightFoot", 2},
                                  {"RightToeBase", 4},
                                  {"RightToeBaseEnd", 5},
                                  {"left_hip", 0},
                                  {"left_knee", 7},
                                  {"left_ankle", 8},
                                  {"left_foot", 9},
                                  {"Spine", 0},
                                  {"Head", 11},
                                  {"jaw", 12},
                                  {"left_eye", 12},
                                  {"LeftHand", 11},
                                  {"LeftHandIndex1", 15},
                                  {"LeftHandIndex2", 16}});
  const LifelikeJoints j = lifelike_joints(s);
  ASSERT_EQ(j.knees.size(), 2u);
  EXPECT_EQ(j.knees[0].parent, 1);
  EXPECT_EQ(j.knees[0].knee, 2);
  EXPECT_EQ(j.knees[0].child, 4);  // the foot chain (3 joints), not the leaf RightLegEnd
  EXPECT_EQ(j.knees[1].parent, 7);
  EXPECT_EQ(j.knees[1].knee, 8);
  EXPECT_EQ(j.knees[1].child, 9);
  // No root, no leaves (RightLegEnd, RightToeBaseEnd, left_foot, jaw, left_eye, LeftHandIndex2),
  // no finger (LeftHandIndex1).
  EXPECT_EQ(j.body, (std::vector<int>{1, 2, 4, 5, 7, 8, 9, 11, 12, 15}));
  EXPECT_EQ(j.feet, (std::vector<int>{4, 9, 10}));  // RightFoot, left_ankle, left_foot; no toe, no end
}

TEST(Lifelike, BendAngleIsZeroWhenStraight) {
  const Eigen::Vector3d hip(0, 100, 0), knee(0, 50, 0);
  EXPECT_NEAR(bend_angle_deg(hip, knee, Eigen::Vector3d(0, 0, 0)), 0.0, 1e-12);
  EXPECT_NEAR(bend_angle_deg(hip, knee, Eigen::Vector3d(0, 50, 30)), 90.0, 1e-12);
  // The shin turned 60 degrees forward from straight down.
  EXPECT_NEAR(bend_angle_deg(hip, knee, Eigen::Vector3d(0, 50 - 25, 25 * std::sqrt(3.0))), 60.0, 1e-12);
  EXPECT_NEAR(bend_angle_deg(hip, knee, knee), 0.0, 1e-12);  // a bone of length 0
}

TEST(Lifelike, LongestRunBelowIsStrict) {
  EXPECT_EQ(longest_run_below({1, 0, 0, 2, 0, 0, 0, 1}, 1.0), 3);
  EXPECT_EQ(longest_run_below({1, 1, 1}, 1.0), 0);
  EXPECT_EQ(longest_run_below({}, 1.0), 0);
}

// Joints: 0 root, 1 hip, 2 knee, 3 ankle (also the foot), 4 toe (a leaf).
LifelikeJoints leg_joints() {
  LifelikeJoints j;
  j.knees = {{1, 2, 3}};
  j.body = {1, 2, 3};
  j.feet = {3};
  return j;
}

// A standing leg whose shin turns forward by bend_deg[t] at frame t; the root stays put.
Eigen::MatrixXd bending_leg(const std::vector<double>& bend_deg) {
  Eigen::MatrixXd p(static_cast<Eigen::Index>(bend_deg.size()), 15);
  for (Eigen::Index t = 0; t < p.rows(); ++t) {
    const double a = bend_deg[static_cast<std::size_t>(t)] * 3.14159265358979323846 / 180.0;
    p.row(t) << 0, 100, 0, 0, 95, 0, 0, 50, 0, 0, 50 - 45 * std::cos(a), 45 * std::sin(a), 0, 50 - 45 * std::cos(a),
        45 * std::sin(a) + 10;
  }
  return p;
}

TEST(Lifelike, KneeShareCountsFramesBentBeyondTheReferencesNinetiethPercentile) {
  const LifelikeParams params;
  // The reference bends 0, 10, ..., 90 degrees: its 90th percentile is 81 (numpy's linear
  // interpolation: 0.9 * 9 = 8.1 between 80 and 90).
  std::vector<double> ref_bend;
  for (int i = 0; i < 10; ++i) ref_bend.push_back(10.0 * i);
  const LifelikeJoints j = leg_joints();
  const LifelikeReference ref = lifelike_reference({lifelike_facts(bending_leg(ref_bend), 30, j, params)}, params);
  EXPECT_NEAR(ref.knee_p90_deg, 81.0, 1e-9);
  // Straight for 7 frames, then bent 85 degrees for 3: 3 of 10 frames beyond 81 = 0.3, three
  // times the reference's own 0.1.
  const std::vector<double> out_bend = {0, 0, 0, 0, 0, 0, 0, 85, 85, 85};
  const LifelikeMotion m = lifelike_motion(lifelike_facts(bending_leg(out_bend), 30, j, params), ref, params);
  EXPECT_NEAR(m.knee_share_ratio, 3.0, 1e-9);
  EXPECT_NEAR(m.knee_p90_deg, 85.0, 1e-9);
  EXPECT_NEAR(m.reference_knee_p90_deg, 81.0, 1e-9);
  // A motion scored against itself as the reference: the share of frames above its own 90th
  // percentile 81 is the one frame at 90, 0.1: ratio 1.
  const LifelikeMotion self = lifelike_motion(lifelike_facts(bending_leg(ref_bend), 30, j, params), ref, params);
  EXPECT_NEAR(self.knee_share_ratio, 1.0, 1e-9);
}

// Legs that hold one pose: the 90th percentile equals every bend, and a bend that differs from it
// by rounding alone (1e-9 degrees) is not beyond it; one bent a degree more is.
TEST(Lifelike, KneeShareIgnoresRoundingAtATie) {
  const LifelikeParams params;
  const LifelikeJoints j = leg_joints();
  const LifelikeReference ref =
      lifelike_reference({lifelike_facts(bending_leg(std::vector<double>(10, 30.0)), 30, j, params)}, params);
  EXPECT_NEAR(ref.knee_p90_deg, 30.0, 1e-9);
  const std::vector<double> rounded = {30, 30, 30 + 1e-9, 30 + 1e-9, 30, 30, 30, 30, 30, 30};
  EXPECT_EQ(lifelike_motion(lifelike_facts(bending_leg(rounded), 30, j, params), ref, params).knee_share_ratio, 0.0);
  const std::vector<double> bent = {30, 30, 31, 31, 30, 30, 30, 30, 30, 30};
  EXPECT_NEAR(lifelike_motion(lifelike_facts(bending_leg(bent), 30, j, params), ref, params).knee_share_ratio, 2.0,
              1e-9);
}

// One body joint moving along x by the given steps (cm per frame); `root_cubed` moves the root by
// root_cubed * t^3 (the joint with it), which the root-relative metrics must not see.
Eigen::MatrixXd stepping_joint(const std::vector<double>& steps, double root_cubed = 0.0) {
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(steps.size()) + 1, 6);
  double x = 0.0;
  for (Eigen::Index t = 0; t < p.rows(); ++t) {
    if (t > 0) x += steps[static_cast<std::size_t>(t - 1)];
    const double root = root_cubed * static_cast<double>(t * t * t);
    p.row(t) << root, 90, 0, root + x, 150, 0;
  }
  return p;
}

LifelikeJoints one_body_joint() {
  LifelikeJoints j;
  j.body = {1};
  return j;
}

TEST(Lifelike, BodyJerkIsTheRootRelativeThirdDifference) {
  const LifelikeParams params;
  const double fps = 10.0;
  // x(t) = c t^3 has third difference 6 c every frame: jerk 6 c fps^3.
  auto cubic = [](double c, int frames) {
    Eigen::MatrixXd p = Eigen::MatrixXd::Zero(frames, 9);
    for (int t = 0; t < frames; ++t) {
      const double root = 7.0 * t * t * t;  // a root that jerks too: root-relative, it does not count
      p.row(t) << root, 90, 0, root + c * t * t * t, 150, 0, root + 20, 150, 0;  // joint 2 rides the root
    }
    return p;
  };
  LifelikeJoints j;
  j.body = {1, 2};
  const LifelikeFacts ref = lifelike_facts(cubic(2.0, 20), fps, j, params);
  // Mean over 17 frames and 2 joints: (12 + 0) / 2 * 1000.
  EXPECT_NEAR(ref.jerk_sum / static_cast<double>(ref.jerk_count), 6000.0, 1e-6);
  EXPECT_EQ(ref.jerk_count, 17 * 2);
  const LifelikeReference r = lifelike_reference({ref}, params);
  EXPECT_NEAR(r.jerk_p99, 12000.0, 1e-6);  // the largest joint's, every frame
  const LifelikeMotion m = lifelike_motion(lifelike_facts(cubic(1.0, 12), fps, j, params), r, params);
  EXPECT_NEAR(m.body_jerk_ratio, 0.5, 1e-9);
  EXPECT_NEAR(m.body_jerk_p99_ratio, 0.5, 1e-9);
}

TEST(Lifelike, AStepsJerkSpreadsOverThreeFrames) {
  const LifelikeParams params;
  // A 1 cm step at frame 4 of 10 (fps 1): third differences 1, -2, 1 at t = 1, 2, 3, so the
  // per-frame jerk is 0, 1, 2, 1, 0, 0, 0 (mean 4/7, 99th percentile 0.99 * 6 = 5.94 between
  // the sorted 1 and 2: 1.94).
  const LifelikeFacts a = lifelike_facts(stepping_joint({0, 0, 0, 1, 0, 0, 0, 0, 0}), 1.0, one_body_joint(), params);
  EXPECT_EQ(a.jerk_frame_max, (std::vector<double>{0, 1, 2, 1, 0, 0, 0}));
  const LifelikeReference r = lifelike_reference({a}, params);
  EXPECT_NEAR(r.jerk_mean, 4.0 / 7.0, 1e-12);
  EXPECT_NEAR(r.jerk_p99, 1.94, 1e-12);
  // The same step in 7 frames: 1, 2, 1, 0 (mean 1, 99th percentile 0.99 * 3 = 2.97: 1.97).
  const LifelikeFacts b = lifelike_facts(stepping_joint({0, 0, 1, 0, 0, 0}), 1.0, one_body_joint(), params);
  const LifelikeMotion m = lifelike_motion(b, r, params);
  EXPECT_NEAR(m.body_jerk_ratio, 7.0 / 4.0, 1e-12);
  EXPECT_NEAR(m.body_jerk_p99_ratio, 1.97 / 1.94, 1e-12);
  // Against a reference that never jerks, the ratios are undefined.
  const LifelikeReference calm =
      lifelike_reference({lifelike_facts(stepping_joint({1, 1, 1, 1, 1}), 1.0, one_body_joint(), params)}, params);
  EXPECT_TRUE(std::isnan(lifelike_motion(b, calm, params).body_jerk_ratio));
}

TEST(Lifelike, LongestStillRunAgainstTheReferencesFifthPercentileSpeed) {
  const LifelikeParams params;
  const double fps = 10.0;
  // Reference: 10 slow frames at 1.0, 1.1, ..., 1.9 cm/s, then 90 frames at 5 cm/s. Its 5th
  // percentile speed: 0.05 * 99 = 4.95, between the 5th and 6th slowest: 1.4 + 0.95 * 0.1 = 1.495.
  // Below it: the 5 frames at 1.0 .. 1.4, in a row: the reference's longest still run is 5 frames.
  std::vector<double> ref_steps;
  for (int i = 0; i < 10; ++i) ref_steps.push_back((1.0 + 0.1 * i) / fps);
  for (int i = 0; i < 90; ++i) ref_steps.push_back(5.0 / fps);
  const LifelikeReference r =
      lifelike_reference({lifelike_facts(stepping_joint(ref_steps), fps, one_body_joint(), params)}, params);
  EXPECT_NEAR(r.still_speed_cm_s, 1.495, 1e-9);
  EXPECT_EQ(r.still_longest_frames, 5);
  // Output: 8 frames at 0.5 cm/s between moving frames, and a second, shorter still run of 3.
  std::vector<double> out_steps(20, 5.0 / fps);
  for (int i = 4; i < 12; ++i) out_steps[static_cast<std::size_t>(i)] = 0.5 / fps;
  for (int i = 15; i < 18; ++i) out_steps[static_cast<std::size_t>(i)] = 0.0;
  const LifelikeMotion m =
      lifelike_motion(lifelike_facts(stepping_joint(out_steps, 3.0), fps, one_body_joint(), params), r, params);
  EXPECT_NEAR(m.still_longest_ratio, 8.0 / 5.0, 1e-12);
  EXPECT_NEAR(m.still_longest_s, 0.8, 1e-12);
  EXPECT_NEAR(m.reference_still_longest_s, 0.5, 1e-12);
}

TEST(Lifelike, StillRunsOfAReferenceOfTwoClipsStayInTheirClip) {
  const LifelikeParams params;
  const double fps = 10.0;
  // Two clips, each ending or starting with 3 slow frames: pooled, their 5th percentile is
  // between the slow ones, but the runs do not join across the clips: 3 frames, not 4.
  std::vector<double> a(40, 5.0 / fps), b(40, 5.0 / fps);
  for (int i = 0; i < 3; ++i) {
    a[static_cast<std::size_t>(37 + i)] = (1.0 + 0.1 * i) / fps;
    b[static_cast<std::size_t>(i)] = (1.5 + 0.1 * i) / fps;
  }
  const LifelikeJoints j = one_body_joint();
  const LifelikeReference r = lifelike_reference(
      {lifelike_facts(stepping_joint(a), fps, j, params), lifelike_facts(stepping_joint(b), fps, j, params)}, params);
  // 80 speeds, 0.05 * 79 = 3.95: between the 4th (1.5) and 5th (1.6) slowest: 1.595.
  EXPECT_NEAR(r.still_speed_cm_s, 1.595, 1e-9);
  EXPECT_EQ(r.still_longest_frames, 3);
}

// One foot (joint 1) at the given heights (cm) and x positions, the root still.
Eigen::MatrixXd foot_path(const std::vector<double>& y, const std::vector<double>& x) {
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(y.size()), 6);
  for (Eigen::Index t = 0; t < p.rows(); ++t)
    p.row(t) << 0, 90, 0, x[static_cast<std::size_t>(t)], y[static_cast<std::size_t>(t)], 0;
  return p;
}

TEST(Lifelike, FootSlidesWhenLowAndFastHorizontally) {
  const LifelikeParams params;
  const double fps = 10.0;
  LifelikeJoints j;
  j.body = {1};
  j.feet = {1};
  // 11 frames. Frames 1-3 creep at 5 cm/s (slow: no slide); frame 4 rises 2.5 cm straight up (25
  // cm/s, but vertically: no slide); frames 5-7 slide on the floor at 20 cm/s; frames 8-10 are
  // lifted 20 cm and move at 50 cm/s (not low: no slide). Its low height (5th percentile) is 0.
  const std::vector<double> y = {0, 0, 0, 0, 2.5, 0, 0, 0, 20, 20, 20};
  const std::vector<double> x = {0, 0.5, 1, 1.5, 1.5, 3.5, 5.5, 7.5, 12.5, 17.5, 22.5};
  const LifelikeFacts f = lifelike_facts(foot_path(y, x), fps, j, params);
  EXPECT_EQ(f.slide_frames, 3);
  EXPECT_EQ(f.slide_of, 10);
  // The reference slides in 1 of its 10 frame steps: the output slides 3 times as often.
  const std::vector<double> ry = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const std::vector<double> rx = {0, 0, 0, 0, 0, 3, 3, 3, 3, 3, 3};
  const LifelikeReference r = lifelike_reference({lifelike_facts(foot_path(ry, rx), fps, j, params)}, params);
  EXPECT_NEAR(r.foot_slide_share, 0.1, 1e-12);
  const LifelikeMotion m = lifelike_motion(f, r, params);
  EXPECT_NEAR(m.foot_slide_share, 0.3, 1e-12);
  EXPECT_NEAR(m.foot_slide_ratio, 3.0, 1e-12);
  // A reference whose feet never slide leaves the ratio undefined.
  const LifelikeReference still =
      lifelike_reference({lifelike_facts(foot_path(ry, std::vector<double>(11, 0.0)), fps, j, params)}, params);
  EXPECT_TRUE(std::isnan(lifelike_motion(f, still, params).foot_slide_ratio));
}

TEST(Lifelike, BadParametersAndShortReferencesAreErrors) {
  LifelikeParams p;
  p.knee_percentile = 100.0;
  EXPECT_THROW(check_lifelike_params(p), Error);
  p = {};
  p.foot_height_cm = 0.0;
  EXPECT_THROW(check_lifelike_params(p), Error);
  p = {};
  const LifelikeFacts three = lifelike_facts(stepping_joint({1, 1}), 30, one_body_joint(), p);
  try {
    lifelike_reference({three}, p);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("jerk needs 4"), std::string::npos) << e.what();
  }
  LifelikeJoints wrong;
  wrong.body = {5};
  EXPECT_THROW(lifelike_facts(stepping_joint({1, 1, 1}), 30, wrong, p), Error);
}

}  // namespace
}  // namespace gmg
