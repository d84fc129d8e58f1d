// Segmentation, beam search, fallbacks, blending and the reenactment pipeline.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "engine/assemble/blend.h"
#include "engine/motion/bvh.h"
#include "engine/app/cli.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/app/pipeline.h"
#include "engine/app/synth/synth.h"
#include "search/beam_search.h"
#include "search/planner.h"
#include "search/segmentation.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

TEST(Segmentation, BoundariesAndTerminationKinds) {
  const auto subs = segment_speech(100, {10, 40, 40, 0, 100, 120}, {{25, "big"}, {40, "this"}});
  ASSERT_EQ(subs.size(), 4u);
  EXPECT_EQ(subs[0].start, 0);
  EXPECT_EQ(subs[0].length, 10);
  EXPECT_EQ(subs[0].kind, Termination::Rhythm);
  EXPECT_EQ(subs[1].length, 15);
  EXPECT_EQ(subs[1].kind, Termination::Keyword);
  EXPECT_EQ(subs[1].keyword, "big");
  EXPECT_EQ(subs[2].keyword, "this");  // 40 is both onset and keyword: keyword wins
  EXPECT_EQ(subs[3].start, 40);
  EXPECT_EQ(subs[3].length, 60);
  EXPECT_EQ(subs[3].kind, Termination::Rhythm);
  const auto none = segment_speech(50, {}, {});
  ASSERT_EQ(none.size(), 1u);
  EXPECT_EQ(none[0].length, 50);
}

// A graph of n frames in one natural chain, with given onset/keyword/break nodes and extra
// unnatural edges. The motion is a rest pose (search does not look at it).
MotionGraph chain_graph(int n, const std::vector<int>& onsets, const std::vector<std::pair<int, std::string>>& keywords,
                        const std::vector<Transition>& jumps) {
  MotionGraph g;
  Skeleton sk;
  Joint root;
  root.name = "root";
  root.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition, Channel::Zrotation, Channel::Xrotation,
                   Channel::Yrotation};
  sk.joints = {root};
  g.motion = motion_rest(sk, 30.0, n);
  for (int f = 0; f < n; ++f) g.motion.translations[static_cast<std::size_t>(f)] = glm::dvec3(f, 0, 0);
  g.clips = {{"chain", 0, n}};
  g.graph = GraphStorage(static_cast<std::size_t>(n));
  for (int f : onsets) g.graph[static_cast<std::size_t>(f)].kinds |= kOnsetNode;
  for (const auto& [f, w] : keywords) {
    g.graph[static_cast<std::size_t>(f)].kinds |= kKeywordNode;
    g.graph[static_cast<std::size_t>(f)].keyword = w;
  }
  g.graph[static_cast<std::size_t>(n - 1)].kinds |= kBreakNode;
  for (int f = 0; f + 1 < n; ++f) boost::add_edge(static_cast<std::size_t>(f), static_cast<std::size_t>(f + 1), EdgeInfo{0.0, true}, g.graph);
  for (const Transition& t : jumps)
    boost::add_edge(static_cast<std::size_t>(t.from), static_cast<std::size_t>(t.to), EdgeInfo{t.weight, false}, g.graph);
  return g;
}

TEST(BeamSearch, FindsTheKnownBestPath) {
  // Onset at 12; a cheap jump 3 -> 22 leads to the onset at 30 in 13 nodes too, but costs 0.05
  // more. Target 12: the natural 0..12 (13 nodes, cost |1 - 13/12|) is the best.
  const MotionGraph g = chain_graph(40, {12, 30}, {}, {{3, 22, 0.05}});
  BeamRequest req;
  req.start_nodes = {0};
  req.target_length = 12;
  const BeamResult r = beam_search(g, req, SearchParams{});
  ASSERT_TRUE(r.accepted);
  std::vector<int> expected(13);
  for (int i = 0; i <= 12; ++i) expected[static_cast<std::size_t>(i)] = i;
  EXPECT_EQ(r.path, expected);
  EXPECT_NEAR(r.cost, 1.0 / 12.0, 1e-12);
}

TEST(BeamSearch, RespectsKeywordTermination) {
  // Keyword "big" at 25 is reachable in 8 nodes only through the jump 3 -> 22.
  const MotionGraph g = chain_graph(40, {5, 12}, {{25, "big"}, {6, "small"}}, {{3, 22, 0.2}});
  BeamRequest req;
  req.start_nodes = {0};
  req.target_length = 8;
  req.kind = Termination::Keyword;
  req.keyword = "big";
  const BeamResult r = beam_search(g, req, SearchParams{});
  ASSERT_TRUE(r.accepted);
  EXPECT_EQ(r.path, (std::vector<int>{0, 1, 2, 3, 22, 23, 24, 25}));
  EXPECT_NEAR(r.cost, 0.2, 1e-12);
}

TEST(BeamSearch, AcceptsOnlyLengthsWithinTenPercent) {
  const MotionGraph g = chain_graph(40, {12}, {}, {});
  BeamRequest req;
  req.start_nodes = {0};
  // The only stops are 12 (13 nodes) and the break at 39 (40 nodes).
  for (int target : {11, 12, 13, 14}) {  // 0.9 t <= 13 <= 1.1 t  <=>  11.8 <= t <= 14.4
    req.target_length = target;
    EXPECT_EQ(beam_search(g, req, SearchParams{}).accepted, target >= 12) << target;
  }
  req.target_length = 20;
  EXPECT_FALSE(beam_search(g, req, SearchParams{}).accepted);
  // The break at 39 would fit a target of 37, but the path terminates at the onset 12 first
  // and terminated paths are not extended (fallback 2 exists for this).
  req.target_length = 37;
  EXPECT_FALSE(beam_search(g, req, SearchParams{}).accepted);
}

TEST(BeamSearch, ResultIsResampledToExactlyTheTarget) {
  const MotionGraph g = chain_graph(40, {12}, {}, {});
  BeamRequest req;
  req.start_nodes = {0};
  req.target_length = 12;
  const BeamResult r = beam_search(g, req, SearchParams{});
  ASSERT_TRUE(r.accepted);
  const Motion m = resample_path(g.motion, r.path, 12);
  EXPECT_EQ(m.frame_count, 12);
  // Even spacing: frame i sits at path position i * 12 / 11; the root x equals the frame index.
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(m.translation(i, 0).x, i * 12.0 / 11.0, 1e-9);
}

Plan plan_one(const MotionGraph& g, const std::vector<Subsequence>& subs, bool fallbacks) {
  SearchParams p;
  p.fallbacks = fallbacks;
  std::mt19937_64 rng(1);
  return plan_reenactment(g, subs, p, rng);
}

TEST(Fallbacks, KeywordFallsBackToRhythm) {
  const MotionGraph g = chain_graph(60, {10, 20, 30, 40, 50}, {{15, "big"}}, {});
  const Plan plan = plan_one(g, {{0, 10, Termination::Keyword, "zebra"}}, true);
  EXPECT_EQ(plan.segments[0].fallback, Fallback::KeywordToRhythm);
  EXPECT_TRUE(plan.segments[0].accepted);
  EXPECT_EQ(plan.fallback_count(Fallback::KeywordToRhythm), 1);
  const Plan off = plan_one(g, {{0, 10, Termination::Keyword, "zebra"}}, false);
  EXPECT_EQ(off.failure_count(), 1);
  EXPECT_TRUE(off.segments[0].failure);
  EXPECT_EQ(off.fallback_count(Fallback::KeywordToRhythm), 0);
}

TEST(Fallbacks, PathsStoppingTooEarlyIgnoreStops) {
  // Onsets every 4 frames: every path terminates after <= 5 nodes; a 30-frame target needs
  // paths that run through stops.
  std::vector<int> onsets;
  for (int f = 4; f < 200; f += 4) onsets.push_back(f);
  const MotionGraph g = chain_graph(200, onsets, {}, {});
  const Plan plan = plan_one(g, {{0, 30, Termination::Rhythm, ""}}, true);
  EXPECT_EQ(plan.segments[0].fallback, Fallback::IgnoreStops);
  EXPECT_TRUE(plan.segments[0].accepted);
  const std::size_t n = plan.segments[0].path.size();
  EXPECT_GE(n, 27u);
  EXPECT_LE(n, 33u);
  EXPECT_EQ(plan.fallback_count(Fallback::IgnoreStops), 1);
  EXPECT_EQ(plan_one(g, {{0, 30, Termination::Rhythm, ""}}, false).failure_count(), 1);
}

TEST(Fallbacks, HopelessTargetHoldsTheLastFrame) {
  const MotionGraph g = chain_graph(20, {5, 10}, {}, {});
  const Plan plan = plan_one(g, {{0, 10, Termination::Rhythm, ""}, {10, 300, Termination::Rhythm, ""}}, true);
  ASSERT_EQ(plan.segments.size(), 2u);
  EXPECT_TRUE(plan.segments[0].accepted);
  EXPECT_EQ(plan.segments[1].fallback, Fallback::HoldLastFrame);
  EXPECT_EQ(plan.segments[1].path, std::vector<int>{plan.segments[0].path.back()});
  EXPECT_EQ(plan.fallback_count(Fallback::HoldLastFrame), 1);
  const Plan off = plan_one(g, {{0, 10, Termination::Rhythm, ""}, {10, 300, Termination::Rhythm, ""}}, false);
  EXPECT_EQ(off.failure_count(), 1);
  // Even a failure yields frames: the assembled motion has the full length.
  EXPECT_EQ(assemble_motion(g, off, BlendParams{}).frame_count, 310);
}

TEST(Planner, ContinuesFromThePreviousPathsSuccessors) {
  // The last onset is far from the clip end, so every accepted first path ends on an onset
  // with successors.
  const MotionGraph g = chain_graph(150, {10, 20, 30, 40, 50, 60, 70, 80, 90, 100}, {}, {});
  const Plan plan = plan_one(g, {{0, 10, Termination::Rhythm, ""}, {10, 10, Termination::Rhythm, ""}}, true);
  ASSERT_TRUE(plan.segments[1].accepted);
  EXPECT_TRUE(plan.segments[1].continued);
  EXPECT_EQ(plan.segments[1].path.front(), plan.segments[0].path.back() + 1);
}

TEST(Planner, KeyFeatureHasTrailingZeros) {
  const std::vector<double> f = key_feature({0, 5, 12, 20}, 1, 4);
  EXPECT_EQ(f, (std::vector<double>{7, 8, 0, 0}));
}

// ---- blending ----

// One joint chain (root + arm + hand): the arm turns about Z by the given angles.
Motion arm_motion(const std::vector<double>& angles) {
  Skeleton sk;
  Joint root;
  root.name = "root";
  root.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition, Channel::Zrotation, Channel::Xrotation,
                   Channel::Yrotation};
  Joint arm;
  arm.name = "arm";
  arm.parent = 0;
  arm.offset = glm::dvec3(0, 10, 0);
  arm.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  Joint hand;
  hand.name = "hand";
  hand.parent = 1;
  hand.offset = glm::dvec3(30, 0, 0);
  hand.channels = arm.channels;
  sk.joints = {root, arm, hand};
  Motion m = motion_rest(sk, 30.0, static_cast<int>(angles.size()));
  for (int f = 0; f < m.frame_count; ++f)
    m.rotations[m.index(f, 1)] = glm::angleAxis(angles[static_cast<std::size_t>(f)], glm::dvec3(0, 0, 1));
  return m;
}

double max_step(const Eigen::MatrixXd& p, int from, int to) {
  double worst = 0.0;
  for (int f = std::max(1, from); f < std::min<int>(static_cast<int>(p.rows()), to); ++f)
    worst = std::max(worst, (p.row(f) - p.row(f - 1)).norm());
  return worst;
}

std::vector<double> ramp(double from, double step, int n) {
  std::vector<double> out;
  for (int i = 0; i < n; ++i) out.push_back(from + step * i);
  return out;
}

// Hand positions of an arm whose angle follows `angles`.
Eigen::MatrixXd hand_path(const std::vector<double>& angles) { return motion_forward_kinematics(arm_motion(angles)); }

TEST(Blend, JunctionHasNoJump) {
  // Left sweeps up at 0.04 rad/frame and ends at 1.16. Right pieces as graph transitions give
  // them: (a) 0.24 rad behind where left was heading, sweeping on; (b) exactly where left was
  // heading (a continuous join); (c) turning back from left's last pose. With the default
  // (offset) blend no step across the junction exceeds the largest step of the inputs near it.
  const std::vector<double> a = ramp(0.0, 0.04, 30);
  const std::vector<std::vector<double>> rights = {ramp(0.96, 0.04, 30), ramp(1.20, 0.04, 30), ramp(1.16, -0.04, 30)};
  BlendParams params;  // defaults: offset, sigmoid, l_blend 4
  for (const BlendCurve curve : {BlendCurve::Linear, BlendCurve::Sigmoid}) {
    params.curve = curve;
    for (const std::vector<double>& b : rights) {
      const Motion left = arm_motion(a), right = arm_motion(b);
      const Motion out = blend_concatenate({left, right}, params);
      ASSERT_EQ(out.frame_count, 60);
      const double inputs = std::max(max_step(hand_path(a), 20, 30), max_step(hand_path(b), 0, 10));
      EXPECT_LE(max_step(motion_forward_kinematics(out), 20, 40), inputs * (1.0 + 1e-9)) << enum_name(kBlendCurveNames, curve) << " from " << b[0];
      // Away from the junction the pieces are untouched.
      EXPECT_LT(rotation_angle_between(out.rotation(10, 1), left.rotation(10, 1)), 1e-9);
      EXPECT_LT(rotation_angle_between(out.rotation(50, 1), right.rotation(20, 1)), 1e-9);
    }
  }
  // A continuous join comes out exactly as the raw concatenation.
  const Motion joined = blend_concatenate({arm_motion(a), arm_motion(rights[1])}, params);
  const Motion whole = arm_motion(ramp(0.0, 0.04, 60));
  for (int f = 0; f < 60; ++f) EXPECT_LT(rotation_angle_between(joined.rotation(f, 1), whole.rotation(f, 1)), 1e-7) << f;
  // Without blending, case (a) jumps back by 0.2 rad: the check above can fail.
  params.l_blend = 0;
  const double raw = max_step(motion_forward_kinematics(blend_concatenate({arm_motion(a), arm_motion(rights[0])}, params)), 20, 40);
  EXPECT_GT(raw, 4.0 * max_step(hand_path(a), 20, 30));
}

TEST(Blend, GapAlongTheMotionIsSpreadEvenly) {
  // Right starts 0.12 rad ahead of where left was heading: that gap must be covered somewhere;
  // linear offset blending adds exactly 0.12 / (L_l + L_r + 1) to each of the 9 steps.
  BlendParams params;
  params.curve = BlendCurve::Linear;
  params.l_blend = 4;
  const Eigen::MatrixXd p =
      motion_forward_kinematics(blend_concatenate({arm_motion(ramp(0.0, 0.04, 30)), arm_motion(ramp(1.32, 0.04, 30))}, params));
  const double radius = 30.0;
  auto chord = [&](double angle) { return radius * 2.0 * std::sin(angle / 2.0); };
  for (int f = 26; f <= 34; ++f) EXPECT_NEAR((p.row(f) - p.row(f - 1)).norm(), chord(0.04 + 0.12 / 9.0), 1e-9) << f;
  EXPECT_NEAR((p.row(25) - p.row(24)).norm(), chord(0.04), 1e-9);
  EXPECT_NEAR((p.row(36) - p.row(35)).norm(), chord(0.04), 1e-9);
}

TEST(Blend, CrossfadeSpreadsTheJump) {
  // SPEC's literal cross-fade (blend_mode=crossfade). A step inside it is
  // (1-w) dA + w dB + dw (B - A), and |B - A| is at most the gap g plus the motion lost while
  // one side is held (n steps of v), so with linear weights no step exceeds
  // v + (g + n v) / (n + 1): the 0.3 rad jump is spread over the window.
  const std::vector<double> a = ramp(0.0, 0.04, 30);
  BlendParams params;
  params.mode = BlendMode::Crossfade;
  params.curve = BlendCurve::Linear;
  params.l_blend = 4;
  const int n = 8;
  const double v = 0.04, g = 0.3, radius = 30.0;
  auto chord = [&](double angle) { return radius * 2.0 * std::sin(angle / 2.0); };
  for (const std::vector<double>& b : {ramp(1.46, 0.04, 30), ramp(0.86, -0.04, 30)}) {
    const Motion left = arm_motion(a), right = arm_motion(b);
    const double blended = max_step(motion_forward_kinematics(blend_concatenate({left, right}, params)), 20, 40);
    EXPECT_LE(blended, chord(v + (g + n * v) / (n + 1)) * 1.0001);
    params.l_blend = 0;
    const double raw = max_step(motion_forward_kinematics(blend_concatenate({left, right}, params)), 20, 40);
    params.l_blend = 4;
    EXPECT_NEAR(raw, chord(g), 1e-6);
    EXPECT_LT(blended, 0.5 * raw);
  }
}

TEST(Blend, QuaternionsTakeTheShortArc) {
  std::vector<double> a(10, 0.3), b(10, 0.35);
  Motion left = arm_motion(a), right = arm_motion(b);
  for (int f = 0; f < right.frame_count; ++f) right.rotations[right.index(f, 1)] = -right.rotations[right.index(f, 1)];
  for (const BlendMode mode : {BlendMode::Offset, BlendMode::Crossfade}) {
    BlendParams params;
    params.mode = mode;
    const Motion out = blend_concatenate({left, right}, params);
    for (int f = 1; f < out.frame_count; ++f)
      EXPECT_LT(rotation_angle_between(out.rotation(f, 1), out.rotation(f - 1, 1)), 0.05 + 1e-9) << enum_name(kBlendModeNames, mode) << " " << f;
  }
}

TEST(Blend, WeightsRiseStrictlyInsideZeroOne) {
  for (const BlendCurve curve : {BlendCurve::Linear, BlendCurve::Sigmoid}) {
    double previous = 0.0;
    for (int i = 0; i < 8; ++i) {
      const double w = blend_weight(i, 8, curve);
      EXPECT_GT(w, previous);
      EXPECT_LT(w, 1.0);
      previous = w;
    }
  }
}

// ---- the whole pipeline through the command line ----

int run_cli(std::vector<std::string> args) {
  std::vector<char*> argv;
  args.insert(args.begin(), "gmg");
  for (std::string& a : args) argv.push_back(a.data());
  return cli_main(static_cast<int>(argv.size()), argv.data());
}

class SynthPipeline : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new gmg::testing::TempDir();
    SynthSpec ref;
    ref.duration_s = 40;
    ref.seed = 11;
    synth_write(synth_speaker(ref), dir_->path().string(), "ref");
    SynthSpec test;
    test.duration_s = 15;
    test.seed = 12;
    synth_write(synth_speaker(test), dir_->path().string(), "test");
    ASSERT_EQ(run_cli({"build", "--motion", file("ref.bvh"), "--audio", file("ref.wav"), "--transcript", file("ref.tsv"),
                       "-o", file("ref.gmg")}),
              0);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string file(const std::string& name) { return dir_->file(name); }
  static gmg::testing::TempDir* dir_;
};
gmg::testing::TempDir* SynthPipeline::dir_ = nullptr;

TEST_F(SynthPipeline, SameSeedGivesByteIdenticalOutput) {
  auto run = [&](const std::string& tag, const std::string& seed) {
    EXPECT_EQ(run_cli({"reenact", "--graph", file("ref.gmg"), "--audio", file("test.wav"), "--transcript", file("test.tsv"),
                       "-o", file(tag + ".bvh"), "--report", file(tag + ".json"), "--seed", seed}),
              0);
    return read_file_bytes(file(tag + ".bvh")) + read_file_bytes(file(tag + ".json"));
  };
  const std::string a = run("a", "5");
  const std::string b = run("b", "5");
  EXPECT_EQ(a, b);
  const Motion m = bvh_read(file("a.bvh"));
  EXPECT_EQ(m.frame_count, 15 * 30);
}

TEST_F(SynthPipeline, ReportCountsEverySubsequence) {
  ASSERT_EQ(run_cli({"reenact", "--graph", file("ref.gmg"), "--audio", file("test.wav"), "-o", file("r.bvh"), "--report",
                     file("r.json")}),
            0);
  const nlohmann::json r = nlohmann::json::parse(read_file_bytes(file("r.json")));
  int accepted = 0, fallbacks = 0;
  for (const auto& s : r["subsequences"]) {
    EXPECT_TRUE(s.contains("graph_ranges"));
    accepted += s["accepted"].get<bool>();
    fallbacks += s["fallback"] != "none";
    EXPECT_TRUE(s["accepted"].get<bool>() || s["fallback"] == "hold_last_frame");
  }
  EXPECT_EQ(accepted, r["totals"]["accepted"].get<int>());
  EXPECT_EQ(r["inputs"]["transcript"], nullptr);
  EXPECT_EQ(r["totals"]["subsequences"].get<std::size_t>(), r["subsequences"].size());
}

TEST_F(SynthPipeline, BadInputsFailWithoutOutput) {
  gmg::testing::write_text(file("empty.wav"), "");
  EXPECT_NE(run_cli({"reenact", "--graph", file("ref.gmg"), "--audio", file("empty.wav"), "-o", file("x.bvh")}), 0);
  EXPECT_NE(run_cli({"reenact", "--graph", file("missing.gmg"), "--audio", file("test.wav"), "-o", file("x.bvh")}), 0);
  // A transcript past the audio's end.
  gmg::testing::write_text(file("late.tsv"), "1.0\t1.5\thello\n30.0\t31.0\tbig\n");
  EXPECT_NE(run_cli({"reenact", "--graph", file("ref.gmg"), "--audio", file("test.wav"), "--transcript", file("late.tsv"),
                     "-o", file("x.bvh")}),
            0);
  EXPECT_NE(run_cli({"reenact", "--graph", file("ref.gmg"), "--audio", file("test.wav"), "-o", file("x.bvh"), "--set",
                     "l_npaths=0"}),
            0);
  EXPECT_FALSE(std::filesystem::exists(file("x.bvh")));
}

// ---- real data ----

TEST(RealData, ReenactsBeat2AndZeggsSpeechFromScottsGraph) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string d = gmg::testing::shared_data_dir();
  Config cfg;
  const MotionGraph g = graph_build_from_files(
      {{d + "/beat2_scott/2_scott_0_1_1.bvh", {d + "/beat2_scott/2_scott_0_1_1.wav", d + "/beat2_scott/2_scott_0_1_1.TextGrid"}}},
      cfg);
  const GraphStats s = graph_stats(g);
  EXPECT_EQ(s.onset_nodes, 115);  // librosa finds 115 onsets in this recording
  EXPECT_GT(s.keyword_nodes, 20);
  gmg::testing::TempDir dir;
  struct Case {
    std::string audio, transcript;
    double seconds;
  };
  for (const Case& c : {Case{d + "/beat2_scott/2_scott_0_2_2.wav", d + "/beat2_scott/2_scott_0_2_2.TextGrid", 62.0},
                        Case{d + "/beat2_scott/2_scott_0_3_3.wav", d + "/beat2_scott/2_scott_0_3_3.TextGrid", 68.0},
                        Case{d + "/zeggs/067_Speech_2_x_1_0.wav", "", 68.8}}) {
    const Reenactment r = reenact(g, {c.audio, c.transcript}, cfg, "scott");
    const int expected = r.report["frames"].get<int>();
    EXPECT_NEAR(expected, c.seconds * 30, 30);
    EXPECT_EQ(r.motion.frame_count, expected);
    const std::string out = dir.file("out.bvh");
    bvh_write(out, r.motion);
    const Motion back = bvh_read(out);
    EXPECT_EQ(back.frame_count, expected);
    EXPECT_TRUE(skeletons_match(back.skeleton, g.motion.skeleton));
    int counted = 0;
    for (const PlannedSegment& seg : r.plan.segments) {
      EXPECT_TRUE(seg.accepted || seg.fallback == Fallback::HoldLastFrame) << c.audio;
      counted += seg.fallback != Fallback::None;
    }
    EXPECT_EQ(r.plan.failure_count(), 0);
    const auto& fb = r.report["totals"]["fallbacks"];
    EXPECT_EQ(counted, fb["keyword_to_rhythm"].get<int>() + fb["ignore_stops"].get<int>() + fb["hold_last_frame"].get<int>());
  }
}

}  // namespace
}  // namespace gmg

namespace gmg {
namespace {

TEST(RealData, GeneaSkeletonWithPositionChannelsOnEveryJoint) {
  // The GENEA 2023 files have no audio: pair the motion with synthetic speech of its length.
  GMG_REQUIRE_SHARED_DATA();
  const std::string bvh = gmg::testing::shared_data_dir() + "/genea2023_format/sample1.bvh";
  const Motion ref = bvh_read(bvh);
  gmg::testing::TempDir dir;
  SynthSpec spec;
  spec.duration_s = ref.duration();
  spec.seed = 8;
  synth_write(synth_speaker(spec), dir.path().string(), "speech");
  spec.duration_s = 12.0;
  spec.seed = 9;
  synth_write(synth_speaker(spec), dir.path().string(), "test");
  Config cfg;
  const MotionGraph g = graph_build_from_files({{bvh, {dir.file("speech.wav"), dir.file("speech.tsv")}}}, cfg);
  EXPECT_EQ(g.frame_count(), ref.frame_count);
  const Reenactment r = reenact(g, {dir.file("test.wav"), dir.file("test.tsv")}, cfg, "genea");
  EXPECT_EQ(r.motion.frame_count, 360);
  bvh_write(dir.file("out.bvh"), r.motion);
  const Motion back = bvh_read(dir.file("out.bvh"));
  EXPECT_TRUE(skeletons_match(back.skeleton, ref.skeleton));
  EXPECT_EQ(back.frame_count, 360);
  // Every output frame's translations stay within the reference's per-joint ranges (blending
  // of position channels is linear between reference values).
  for (int j = 0; j < ref.joint_count(); ++j) {
    glm::dvec3 lo(1e30), hi(-1e30);
    for (int f = 0; f < ref.frame_count; ++f) {
      lo = glm::min(lo, ref.translation(f, j));
      hi = glm::max(hi, ref.translation(f, j));
    }
    const glm::dvec3 slack = 0.25 * (hi - lo) + glm::dvec3(1e-3);
    for (int f = 0; f < back.frame_count; f += 7) {
      const glm::dvec3 t = back.translation(f, j);
      EXPECT_TRUE(glm::all(glm::greaterThanEqual(t, lo - slack)) && glm::all(glm::lessThanEqual(t, hi + slack)))
          << ref.skeleton.joints[j].name << " frame " << f;
    }
  }
}

}  // namespace
}  // namespace gmg
