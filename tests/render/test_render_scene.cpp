// gmg render's parts on their own, no ffmpeg needed: captions grouped from the words, the markers'
// badges, the camera of each view, the figure drawn from a skeleton, the encoder's frame rates.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/motion/motion.h"
#include "engine/render/camera.h"
#include "engine/render/encoder.h"
#include "engine/render/figure.h"
#include "engine/render/overlay.h"
#include "engine/synth/synth.h"

namespace gmg {
namespace {

TEST(RenderCaptions, WordsGroupIntoCaptionsAtPausesAndTheCurrentOneIsFound) {
  const std::vector<text::Word> words = {{0.5, 0.8, "hello"}, {0.85, 1.2, "big"}, {2.5, 2.9, "world"}};
  // Width: 10 px per byte, so "hello big" (9 bytes) is 90 px.
  const auto width = [](const std::string& s) { return 10.0 * static_cast<double>(s.size()); };
  const auto captions = render::make_captions(words, 1000, width);
  ASSERT_EQ(captions.size(), 2u);  // the 1.3 s pause splits them
  EXPECT_EQ(captions[0].words.size(), 2u);
  EXPECT_DOUBLE_EQ(captions[0].show, 0.35);
  EXPECT_DOUBLE_EQ(captions[0].hide, 2.2);  // 1 s after "big", cut at 0.15 s before "world"
  EXPECT_DOUBLE_EQ(captions[1].hide, 3.9);
  EXPECT_EQ(render::caption_at(captions, 0.2), nullptr);
  EXPECT_EQ(render::caption_at(captions, 1.0), &captions[0]);
  EXPECT_EQ(render::caption_at(captions, 2.4), &captions[1]);
  EXPECT_EQ(render::caption_at(captions, 4.0), nullptr);
  // Too narrow for two words: one word per caption.
  EXPECT_EQ(render::make_captions(words, 60, width).size(), 3u);
}

TEST(RenderMarkers, ABadgeIsLitForAFifthOfASecondAfterItsEvent) {
  const std::vector<double> times = {1.0, 3.0};
  EXPECT_FALSE(render::badge_lit(times, 0.99));
  EXPECT_TRUE(render::badge_lit(times, 1.0));
  EXPECT_TRUE(render::badge_lit(times, 1.19));
  EXPECT_FALSE(render::badge_lit(times, 1.21));
  EXPECT_TRUE(render::badge_lit(times, 3.1));
  EXPECT_FALSE(render::badge_lit({}, 1.0));
}

TEST(RenderCamera, FrontSideAndTopViewsPutThePersonWhereAViewerExpects) {
  render::Box box;
  box.add({-50, 0, -20});
  box.add({50, 180, 20});
  const render::Rect area{0, 0, 640, 480};
  const glm::dvec3 facing(0, 0, 1), left(30, 100, 0), front(0, 100, 30), head(0, 170, 0), feet(0, 0, 0);
  const render::Camera front_cam = render::camera_fit(box, facing, render::View::Front, area);
  // Facing the viewer: their left hand appears on the right, the head above the feet.
  EXPECT_GT(render::camera_project(front_cam, left).x, render::camera_project(front_cam, glm::dvec3(-30, 100, 0)).x);
  EXPECT_LT(render::camera_project(front_cam, head).y, render::camera_project(front_cam, feet).y);
  // Near parts look larger: the front of the body is nearer than its back.
  EXPECT_LT(render::camera_project(front_cam, front).depth,
            render::camera_project(front_cam, glm::dvec3(0, 100, -30)).depth);
  const render::Camera side = render::camera_fit(box, facing, render::View::Side, area);
  EXPECT_LT(render::camera_project(side, front).x, render::camera_project(side, glm::dvec3(0, 100, -30)).x);
  const render::Camera top = render::camera_fit(box, facing, render::View::Top, area);
  EXPECT_GT(render::camera_project(top, front).y, render::camera_project(top, glm::dvec3(0, 100, -30)).y);
  EXPECT_GT(render::camera_project(top, left).x, render::camera_project(top, glm::dvec3(-30, 100, 0)).x);
  // A person facing +X: the front view looks along -X.
  const render::Camera turned = render::camera_fit(box, glm::dvec3(1, 0, 0), render::View::Front, area);
  EXPECT_NEAR(turned.back.x, std::cos(12.0 * M_PI / 180), 1e-9);
  EXPECT_THROW(render::parse_view("back"), Error);
}

TEST(RenderFigure, BonesComeFromTheSkeletonWithoutFaceHelpersOrAWorldRoot) {
  // A GENEA 2023-like chain: a world root above the body root, eyes, a "_null" end point.
  Skeleton s;
  auto add = [&](const std::string& name, int parent, glm::dvec3 offset) {
    Joint j;
    j.name = name;
    j.parent = parent;
    j.offset = offset;
    s.joints.push_back(j);
  };
  add("body_world", -1, {0, 0, 0});
  add("b_root", 0, {0, 100, 0});      // 1
  add("b_neck0", 1, {0, 50, 0});      // 2
  add("b_head", 2, {0, 10, 0});       // 3
  add("b_l_eye", 3, {3, 5, 8});       // 4
  add("b_head_null", 3, {0, 20, 0});  // 5
  add("b_l_arm", 2, {20, -5, 0});     // 6
  add("b_l_forearm", 6, {28, 0, 0});  // 7
  s.joints[7].has_end_site = true;
  s.joints[7].end_site = {25, 0, 0};
  const render::Figure f = render::figure_from_motion(motion_rest(s, 30, 2));
  std::vector<std::pair<int, int>> bones;
  for (const render::Bone& b : f.bones) bones.emplace_back(b.a, b.b);
  const std::vector<std::pair<int, int>> expected = {{1, 2}, {2, 3}, {2, 6}, {6, 7}, {7, 8}};  // 8: the end site
  EXPECT_EQ(bones, expected);
  EXPECT_EQ(f.head, 3);
  EXPECT_EQ(f.head_base, 2);
  EXPECT_DOUBLE_EQ(f.points(0, 24), 73.0);  // end site: 20 + 28 + 25 cm along +X
  EXPECT_EQ(f.side[6], 1);
  EXPECT_EQ(f.side[2], 0);
  EXPECT_GT(render::joint_radius_cm("Spine1"), render::joint_radius_cm("LeftForeArm"));
  EXPECT_GT(render::joint_radius_cm("left_elbow"), render::joint_radius_cm("left_index2"));
  EXPECT_EQ(render::joint_side("RightHand"), -1);
  EXPECT_EQ(render::joint_side("left_wrist"), 1);
  EXPECT_EQ(render::joint_side("b_r_wrist"), -1);
}

TEST(RenderFigure, TheNoseIsInFrontOfTheHeadAndTurnsWithIt) {
  // The synthetic speaker faces +Z in its rest pose, in centimetres; the head sphere has radius 10,
  // its centre 8 above the head joint, the nose 9.5 in front of that.
  Motion m = motion_rest(synth_skeleton(), 30, 2);
  const int head = m.skeleton.find("Head");
  m.rotations[m.index(1, head)] = glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 1, 0));
  const render::Figure f = render::figure_from_motion(m);
  ASSERT_EQ(f.head, head);
  ASSERT_GE(f.nose, 0);
  for (int frame : {0, 1}) {
    const glm::dvec3 d = render::figure_point(f, frame, f.nose) - render::figure_point(f, frame, head);
    const glm::dvec3 expected = frame == 0 ? glm::dvec3(0, 8, 9.5) : glm::dvec3(9.5, 8, 0);  // +90 deg about Y: z -> x
    EXPECT_NEAR(glm::length(d - expected), 0.0, 1e-9) << frame;
  }
}

TEST(RenderFigure, MetresAreDrawnInCentimetres) {
  Skeleton s;
  Joint root;
  root.name = "Hips";
  s.joints.push_back(root);
  Joint head;
  head.name = "Head";
  head.parent = 0;
  head.offset = {0, 0.6, 0};  // metres: a skeleton under 5 units tall
  s.joints.push_back(head);
  const render::Figure f = render::figure_from_motion(motion_rest(s, 30, 1));
  EXPECT_DOUBLE_EQ(f.points(0, 4), 60.0);
}

TEST(RenderEncoder, FrameRatesBecomeExactFractions) {
  EXPECT_EQ(render::fps_rational(30).num, 30);
  EXPECT_EQ(render::fps_rational(30).den, 1);
  EXPECT_EQ(render::fps_rational(1.0 / 0.0333333).num, 30);  // a BVH's rounded Frame Time
  EXPECT_EQ(render::fps_rational(30000.0 / 1001).num, 30000);
  EXPECT_EQ(render::fps_rational(30000.0 / 1001).den, 1001);
  EXPECT_EQ(render::fps_rational(12.5).num, 12500);
  EXPECT_EQ(render::fps_rational(12.5).den, 1000);
  EXPECT_EQ(render::find_executable("/no/such/tool"), "");
}

}  // namespace
}  // namespace gmg
