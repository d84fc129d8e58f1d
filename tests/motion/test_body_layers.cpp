// The body's two layers (engine/motion/body_layers.h) on rigs built by hand: the synthetic speaker's
// (Mixamo names), SMPL-X in a BVH's depth-first order, a GENEA-like rig, an upper-body-only rig and a
// rig whose names lie. Expected joints are read off each rig's geometry by hand.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/motion/body_layers.h"
#include "engine/synth/synth.h"
#include "tests/motion/motion_test_util.h"

namespace gmg {
namespace {

std::vector<int> indices(const Skeleton& s, const std::vector<std::string>& names) {
  std::vector<int> out;
  for (const std::string& n : names) {
    const int j = s.find(n);
    EXPECT_GE(j, 0) << n;
    out.push_back(j);
  }
  return out;
}

std::vector<std::string> names_where(const Skeleton& s, const std::vector<char>& flags) {
  std::vector<std::string> out;
  for (int j = 0; j < s.joint_count(); ++j)
    if (flags[static_cast<std::size_t>(j)]) out.push_back(s.joints[static_cast<std::size_t>(j)].name);
  return out;
}

std::vector<std::string> names_of(const Skeleton& s, const std::vector<int>& joints) {
  std::vector<std::string> out;
  for (int j : joints) out.push_back(s.joints[static_cast<std::size_t>(j)].name);
  return out;
}

// One frame in the rest pose, the root at `root` (its translation channel).
Motion standing(const Skeleton& s, glm::dvec3 root) {
  Motion m = motion_rest(s, 30.0, 1);
  m.translations[0] = root;
  return m;
}

// SMPL-X joints standing (metres, Y-up, facing +Z): hips at 0.95, feet ends at 0.02, head at 1.69.
Skeleton smplx_standing() {
  const std::map<std::string, glm::dvec3> offsets = {{"left_hip", {0.06, -0.09, 0.0}},
                                                     {"right_hip", {-0.06, -0.09, 0.0}},
                                                     {"spine1", {0.0, 0.11, 0.0}},
                                                     {"left_knee", {0.0, -0.38, 0.0}},
                                                     {"right_knee", {0.0, -0.38, 0.0}},
                                                     {"spine2", {0.0, 0.13, 0.0}},
                                                     {"left_ankle", {0.0, -0.40, 0.0}},
                                                     {"right_ankle", {0.0, -0.40, 0.0}},
                                                     {"spine3", {0.0, 0.05, 0.0}},
                                                     {"left_foot", {0.0, -0.06, 0.12}},
                                                     {"right_foot", {0.0, -0.06, 0.12}},
                                                     {"neck", {0.0, 0.21, 0.0}},
                                                     {"left_collar", {0.07, 0.11, 0.0}},
                                                     {"right_collar", {-0.07, 0.11, 0.0}},
                                                     {"head", {0.0, 0.09, 0.03}},
                                                     {"left_shoulder", {0.11, 0.03, 0.0}},
                                                     {"right_shoulder", {-0.11, 0.03, 0.0}},
                                                     {"left_elbow", {0.26, 0.0, 0.0}},
                                                     {"right_elbow", {-0.26, 0.0, 0.0}},
                                                     {"left_wrist", {0.25, 0.0, 0.0}},
                                                     {"right_wrist", {-0.25, 0.0, 0.0}},
                                                     {"jaw", {0.0, -0.02, 0.05}},
                                                     {"left_eye_smplhf", {0.03, 0.05, 0.08}},
                                                     {"right_eye_smplhf", {-0.03, 0.05, 0.08}}};
  Skeleton s = testing::smplx_depth_first();
  for (Joint& j : s.joints) {
    const auto it = offsets.find(j.name);
    if (it != offsets.end()) {
      j.offset = it->second;
    } else if (j.parent >= 0) {  // a finger segment: 3 cm further out along the arm
      j.offset = glm::dvec3(j.name.rfind("left_", 0) == 0 ? 0.03 : -0.03, 0.0, 0.0);
    }
  }
  return s;
}

Joint joint(const std::string& name, int parent, glm::dvec3 offset) {
  Joint j;
  j.name = name;
  j.parent = parent;
  j.offset = offset;
  j.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  if (parent < 0) j.channels.insert(j.channels.begin(), {Channel::Xposition, Channel::Yposition, Channel::Zposition});
  return j;
}

// A GENEA-like rig: b_root a little below the hips, the thighs hanging from it 8 cm higher, the spine above.
Skeleton genea_like() {
  Skeleton s;
  s.joints = {joint("b_root", -1, {0, 0, 0}),        joint("b_l_upleg", 0, {0.09, 0.08, 0}),
              joint("b_l_leg", 1, {0, -0.45, 0}),    joint("b_l_foot", 2, {0, -0.42, 0}),
              joint("b_l_toe", 3, {0, -0.07, 0.12}), joint("b_r_upleg", 0, {-0.09, 0.08, 0}),
              joint("b_r_leg", 5, {0, -0.45, 0}),    joint("b_r_foot", 6, {0, -0.42, 0}),
              joint("b_r_toe", 7, {0, -0.07, 0.12}), joint("b_spine0", 0, {0, 0.15, 0}),
              joint("b_spine1", 9, {0, 0.12, 0}),    joint("b_neck0", 10, {0, 0.25, 0}),
              joint("b_head", 11, {0, 0.12, 0}),     joint("b_l_shoulder", 10, {0.05, 0.2, 0}),
              joint("b_l_arm", 13, {0.15, 0, 0}),    joint("b_l_forearm", 14, {0.28, 0, 0}),
              joint("b_l_wrist", 15, {0.25, 0, 0}),  joint("b_r_shoulder", 10, {-0.05, 0.2, 0}),
              joint("b_r_arm", 17, {-0.15, 0, 0}),   joint("b_r_forearm", 18, {-0.28, 0, 0}),
              joint("b_r_wrist", 19, {-0.25, 0, 0})};
  return s;
}

const std::vector<std::string> kSynthLower = {"Hips",       "LeftUpLeg", "LeftLeg",   "LeftFoot",    "LeftToeBase",
                                              "RightUpLeg", "RightLeg",  "RightFoot", "RightToeBase"};

TEST(BodyLayers, SynthSpeakerSplitsAtTheHips) {
  const Skeleton s = synth_skeleton();
  const Motion m = standing(s, {0, 95, 0});
  const BodyLayers l = find_body_layers(m);
  ASSERT_TRUE(l.layered());
  ASSERT_EQ(l.lower.size(), static_cast<std::size_t>(s.joint_count()));
  EXPECT_EQ(names_where(s, l.lower), kSynthLower);
  EXPECT_EQ(l.hip_branch, s.find("Hips"));
  // Both toe ends lie on the floor (y 0); the tie goes to the one first in the file.
  EXPECT_EQ(l.feet, indices(s, {"LeftToeBase", "RightToeBase"}));
  EXPECT_EQ(l.legs[0], indices(s, {"LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase"}));
  EXPECT_EQ(l.legs[1], indices(s, {"RightUpLeg", "RightLeg", "RightFoot", "RightToeBase"}));
  // Spine2 is where the neck and both shoulders part.
  EXPECT_EQ(l.spine, indices(s, {"Spine", "Spine1", "Spine2"}));
}

TEST(BodyLayers, SynthSpeakerClipSplitsTheSameWay) {
  SynthSpec spec;
  spec.duration_s = 1.0;
  const SynthClip clip = synth_speaker(spec);
  const BodyLayers l = find_body_layers(clip.motion);
  const Skeleton& s = clip.motion.skeleton;
  EXPECT_EQ(names_where(s, l.lower), kSynthLower);
  EXPECT_EQ(names_of(s, l.spine), (std::vector<std::string>{"Spine", "Spine1", "Spine2"}));
}

TEST(BodyLayers, TwoEndsPerFootPartAtTheAnkleNotTheHips) {
  // A heel end under each foot as well as the toe, all four on the floor: the two lowest ends (left
  // toe and heel) part at the ankle, low down, so the feet are the left toe and the right toe.
  Skeleton s = synth_skeleton();
  for (const char* side : {"Left", "Right"}) {
    const int foot = s.find(std::string(side) + "Foot");
    Joint heel;
    heel.name = std::string(side) + "Heel";
    heel.parent = foot;
    heel.offset = glm::dvec3(0, -6, -4);
    heel.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
    s.joints.insert(s.joints.begin() + foot + 2, heel);  // after the toe, whose parent is foot
    for (std::size_t j = static_cast<std::size_t>(foot) + 3; j < s.joints.size(); ++j)
      if (s.joints[j].parent > foot + 1) ++s.joints[j].parent;
  }
  ASSERT_EQ(s.joints[static_cast<std::size_t>(s.find("LeftHeel"))].parent, s.find("LeftFoot"));
  ASSERT_EQ(s.joints[static_cast<std::size_t>(s.find("RightToeBase"))].parent, s.find("RightFoot"));
  const BodyLayers l = find_body_layers(standing(s, {0, 95, 0}));
  ASSERT_TRUE(l.layered());
  EXPECT_EQ(l.hip_branch, 0);
  EXPECT_EQ(l.feet, indices(s, {"LeftToeBase", "RightToeBase"}));
  EXPECT_EQ(l.legs[0], indices(s, {"LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase", "LeftHeel"}));
  EXPECT_EQ(l.legs[1], indices(s, {"RightUpLeg", "RightLeg", "RightFoot", "RightToeBase", "RightHeel"}));
}

TEST(BodyLayers, FollowsTheFirstFrameNotTheOffsets) {
  // The left leg raised forward to hip height in frame 0: its toe is no longer among the lowest
  // ends, so no two legs reach the floor: nothing is layered.
  const Skeleton s = synth_skeleton();
  Motion m = standing(s, {0, 95, 0});
  m.rotations[m.index(0, s.find("LeftUpLeg"))] = glm::angleAxis(-0.5 * M_PI, glm::dvec3(1, 0, 0));
  EXPECT_FALSE(find_body_layers(m).layered());
}

TEST(BodyLayers, SmplxDepthFirst) {
  const Skeleton s = smplx_standing();
  const BodyLayers l = find_body_layers(standing(s, {0, 0.95, 0}));
  ASSERT_TRUE(l.layered());
  EXPECT_EQ(names_where(s, l.lower),
            (std::vector<std::string>{"pelvis", "left_hip", "left_knee", "left_ankle", "left_foot", "right_hip",
                                      "right_knee", "right_ankle", "right_foot"}));
  EXPECT_EQ(l.hip_branch, s.find("pelvis"));
  EXPECT_EQ(l.feet, indices(s, {"left_foot", "right_foot"}));
  EXPECT_EQ(l.legs[0], indices(s, {"left_hip", "left_knee", "left_ankle", "left_foot"}));
  EXPECT_EQ(l.legs[1], indices(s, {"right_hip", "right_knee", "right_ankle", "right_foot"}));
  EXPECT_EQ(l.spine, indices(s, {"spine1", "spine2", "spine3"}));
  EXPECT_EQ(describe_body_layers(s, l),
            "lower: pelvis left_hip left_knee left_ankle left_foot right_hip right_knee right_ankle right_foot; "
            "spine: spine1 spine2 spine3");
}

TEST(BodyLayers, GeneaRootBelowTheThighs) {
  const Skeleton s = genea_like();
  const BodyLayers l = find_body_layers(standing(s, {0, 0.88, 0}));
  ASSERT_TRUE(l.layered());
  EXPECT_EQ(l.hip_branch, 0);
  EXPECT_EQ(names_where(s, l.lower), (std::vector<std::string>{"b_root", "b_l_upleg", "b_l_leg", "b_l_foot", "b_l_toe",
                                                               "b_r_upleg", "b_r_leg", "b_r_foot", "b_r_toe"}));
  EXPECT_EQ(l.feet, indices(s, {"b_l_toe", "b_r_toe"}));
  EXPECT_EQ(l.spine, indices(s, {"b_spine0", "b_spine1"}));
}

TEST(BodyLayers, RootOnTheFloorIsLowerUpToTheHipBranch) {
  // A world joint on the floor above which the rig hangs: the chain from the root to the hip
  // branch is lower, the hip branch is b_root (where the legs part), not the root.
  Skeleton s = genea_like();
  for (Joint& j : s.joints) j.parent = j.parent + 1;
  s.joints[0].parent = 0;  // b_root now hangs from the new root
  s.joints[0].channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  s.joints[0].offset = glm::dvec3(0, 0.88, 0);
  s.joints.insert(s.joints.begin(), joint("world", -1, {0, 0, 0}));
  const BodyLayers l = find_body_layers(standing(s, {0, 0, 0}));
  ASSERT_TRUE(l.layered());
  EXPECT_EQ(l.hip_branch, s.find("b_root"));
  EXPECT_EQ(names_where(s, l.lower),
            (std::vector<std::string>{"world", "b_root", "b_l_upleg", "b_l_leg", "b_l_foot", "b_l_toe", "b_r_upleg",
                                      "b_r_leg", "b_r_foot", "b_r_toe"}));
  EXPECT_EQ(l.spine, indices(s, {"b_spine0", "b_spine1"}));
}

TEST(BodyLayers, UpperBodyOnlyRigHasNoLayers) {
  Skeleton full = synth_skeleton();
  Skeleton s;
  std::vector<int> map(static_cast<std::size_t>(full.joint_count()), -1);
  for (int j = 0; j < full.joint_count(); ++j) {
    Joint jt = full.joints[static_cast<std::size_t>(j)];
    if (jt.name.find("Leg") != std::string::npos || jt.name.find("Foot") != std::string::npos ||
        jt.name.find("Toe") != std::string::npos)
      continue;
    jt.parent = jt.parent < 0 ? -1 : map[static_cast<std::size_t>(jt.parent)];
    map[static_cast<std::size_t>(j)] = s.joint_count();
    s.joints.push_back(jt);
  }
  ASSERT_EQ(s.joint_count(), 14);
  const BodyLayers l = find_body_layers(standing(s, {0, 95, 0}));
  EXPECT_FALSE(l.layered());
  EXPECT_TRUE(l.lower.empty());
  EXPECT_TRUE(l.spine.empty());
  EXPECT_EQ(l.hip_branch, -1);
  EXPECT_EQ(describe_body_layers(s, l), "one layer (no two legs found)");
}

TEST(BodyLayers, GeometryDecidesNotNames) {
  // The legs named as arms and the arms as legs: the same joints are lower.
  Skeleton s = synth_skeleton();
  const std::vector<int> lower_index = indices(s, kSynthLower);
  const std::vector<std::pair<std::string, std::string>> swap = {
      {"LeftUpLeg", "LeftArm"},     {"LeftLeg", "LeftForeArm"}, {"LeftFoot", "LeftHand"}, {"RightUpLeg", "RightArm"},
      {"RightLeg", "RightForeArm"}, {"RightFoot", "RightHand"}, {"Hips", "Head"},         {"Spine", "Neck"}};
  for (const auto& [a, b] : swap) {
    const int ia = s.find(a), ib = s.find(b);
    std::swap(s.joints[static_cast<std::size_t>(ia)].name, s.joints[static_cast<std::size_t>(ib)].name);
  }
  const BodyLayers l = find_body_layers(standing(s, {0, 95, 0}));
  ASSERT_TRUE(l.layered());
  std::vector<int> lower;
  for (int j = 0; j < s.joint_count(); ++j)
    if (l.lower[static_cast<std::size_t>(j)]) lower.push_back(j);
  EXPECT_EQ(lower, lower_index);
  EXPECT_EQ(l.hip_branch, 0);
  EXPECT_EQ(names_of(s, l.spine), (std::vector<std::string>{"Neck", "Spine1", "Spine2"}));
}

TEST(BodyLayers, NamesOverrideTheGeometry) {
  const Skeleton s = synth_skeleton();
  const Motion m = standing(s, {0, 95, 0});
  std::vector<std::string> names = kSynthLower;
  names.push_back("Spine");
  const BodyLayers l = body_layers_from_names(m, names);
  ASSERT_TRUE(l.layered());
  std::vector<std::string> expected = kSynthLower;
  expected.insert(expected.begin() + 1, "Spine");  // file order
  EXPECT_EQ(names_where(s, l.lower), expected);
  // The spine now starts above the deepest lower joint with an upper child: Spine.
  EXPECT_EQ(l.hip_branch, s.find("Spine"));
  EXPECT_EQ(l.spine, indices(s, {"Spine1", "Spine2"}));
  EXPECT_EQ(l.feet, indices(s, {"LeftToeBase", "RightToeBase"}));
  EXPECT_EQ(describe_body_layers(s, l),
            "lower: Hips Spine LeftUpLeg LeftLeg LeftFoot LeftToeBase RightUpLeg RightLeg RightFoot RightToeBase; "
            "spine: Spine1 Spine2");
}

TEST(BodyLayers, NamesWithoutToesEndTheLegsAtTheFeet) {
  const Skeleton s = synth_skeleton();
  const BodyLayers l = body_layers_from_names(
      standing(s, {0, 95, 0}), {"Hips", "LeftUpLeg", "LeftLeg", "LeftFoot", "RightUpLeg", "RightLeg", "RightFoot"});
  EXPECT_EQ(l.legs[0], indices(s, {"LeftUpLeg", "LeftLeg", "LeftFoot"}));
  EXPECT_EQ(l.legs[1], indices(s, {"RightUpLeg", "RightLeg", "RightFoot"}));
  EXPECT_EQ(l.feet, indices(s, {"LeftFoot", "RightFoot"}));
  EXPECT_EQ(l.lower[static_cast<std::size_t>(s.find("LeftToeBase"))], 0);
}

// With the toes left out of the names, each foot has an upper child (its toe); the spine must
// still be the chain above the hips, where the chest, arms and head hang, not a toe: join_layers
// would otherwise turn the toe by the pelvis difference and leave the real spine alone.
TEST(BodyLayers, NamesWithoutToesKeepTheSpineAboveTheHips) {
  const Skeleton s = synth_skeleton();
  const BodyLayers l = body_layers_from_names(
      standing(s, {0, 95, 0}), {"Hips", "LeftUpLeg", "LeftLeg", "LeftFoot", "RightUpLeg", "RightLeg", "RightFoot"});
  EXPECT_EQ(l.hip_branch, s.find("Hips"));
  EXPECT_EQ(l.spine, indices(s, {"Spine", "Spine1", "Spine2"}));
}

TEST(BodyLayers, UnknownNameThrowsNamingIt) {
  const Motion m = standing(synth_skeleton(), {0, 95, 0});
  try {
    body_layers_from_names(m, {"Hips", "LeftKnee"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'LeftKnee'"), std::string::npos) << e.what();
  }
  try {
    body_layers_from_names(m, {"LeftUpLeg"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'Hips'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gmg
