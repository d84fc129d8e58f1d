// The reenactment pipeline on the shared recordings (skipped without them): BEAT2 and ZEGGS speech
// from BEAT2 scott's graph, a GENEA skeleton with position channels on every joint, the
// naturalness of the reenacted capture, and BEAT2 .npz output that keeps the speaker.
#include <algorithm>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/assemble/timeline.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/metrics/evaluate.h"
#include "engine/metrics/naturalness.h"
#include "engine/motion/bvh.h"
#include "engine/motion/motion_file.h"
#include "engine/motion/npy.h"
#include "engine/motion/zip.h"
#include "engine/pipeline/pipeline.h"
#include "engine/synth/synth.h"
#include "graph/stats.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

TEST(PipelineRealData, ReenactsBeat2AndZeggsSpeechFromScottsGraph) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string d = gmg::testing::shared_data_dir();
  Config cfg;
  const MotionGraph g =
      graph_build_from_files({{d + "/beat2_scott/2_scott_0_1_1.bvh",
                               {d + "/beat2_scott/2_scott_0_1_1.wav", d + "/beat2_scott/2_scott_0_1_1.TextGrid"}}},
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
      EXPECT_TRUE(seg.accepted || seg.fallback == Fallback::HoldLastFrame || seg.fallback == Fallback::ContinueMotion)
          << c.audio;
      counted += seg.fallback != Fallback::None;
    }
    EXPECT_EQ(r.plan.failure_count(), 0);
    const auto& fb = r.report["totals"]["fallbacks"];
    EXPECT_EQ(counted, fb["keyword_to_rhythm"].get<int>() + fb["ignore_stops"].get<int>() +
                           fb["hold_last_frame"].get<int>() + fb["continue_motion"].get<int>());
  }
}

TEST(PipelineRealData, GeneaSkeletonWithPositionChannelsOnEveryJoint) {
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

// The natural-motion targets on the real clip (SPEC "natural transitions"): reenacting new speech of
// the BEAT2 speaker from 2_scott_0_1_1, every output stays as smooth as the capture: largest step
// at most 1.5x the reference's 99.9th-percentile step, root-relative jerk at most 2x the
// reference's, fewer than 0.5 % of frames above that step, root speed from 0.6 to 1.25 x.
TEST(PipelineRealData, ReenactedScottIsAsNaturalAsTheCapture) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string d = gmg::testing::shared_data_dir() + "/beat2_scott/";
  Config cfg;
  const MotionGraph g =
      graph_build_from_files({{d + "2_scott_0_1_1.bvh", {d + "2_scott_0_1_1.wav", d + "2_scott_0_1_1.TextGrid"}}}, cfg);
  const double scale = length_unit_to_cm(g.motion.skeleton);
  const Eigen::MatrixXd ref = motion_forward_kinematics(g.motion) * scale;
  const NaturalnessReference nr = naturalness_reference(ref, g.motion.fps);
  for (const char* test : {"2_scott_0_2_2", "2_scott_0_3_3"}) {
    for (std::uint64_t seed : {1, 2}) {
      cfg.seed = seed;
      const Reenactment r = reenact(g, {d + test + ".wav", d + test + ".TextGrid"}, cfg, "scott");
      const Naturalness n = naturalness(motion_forward_kinematics(r.motion) * scale, g.motion.fps, nr);
      EXPECT_LE(n.jump_ratio, 1.5) << test << " seed " << seed;
      EXPECT_LE(n.jerk_ratio, 2.0) << test << " seed " << seed;
      EXPECT_LT(n.step_share, 0.005) << test << " seed " << seed;
      // The root neither glides nor freezes. The lower body plays long stretches of the capture and
      // rests in the new speech's pauses, so it moves somewhat less than the capture's (0.74 x on
      // 0_3_3, seed 1).
      EXPECT_GT(n.root_speed_ratio, 0.6) << test << " seed " << seed;
      EXPECT_LT(n.root_speed_ratio, 1.25) << test << " seed " << seed;
    }
  }
}
// The sample at source time t of frame-major values with `dims` per frame (linear between frames,
// as the assembly reads a continuous stretch).
double value_at(const std::vector<double>& v, int dims, double t, int c) {
  const auto f = static_cast<std::size_t>(std::floor(t));
  const double a = t - std::floor(t);
  const double x = v[f * static_cast<std::size_t>(dims) + static_cast<std::size_t>(c)];
  if (a == 0.0) return x;
  return (1.0 - a) * x + a * v[(f + 1) * static_cast<std::size_t>(dims) + static_cast<std::size_t>(c)];
}

double median_of(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

TEST(PipelineRealData, Beat2NpzOutputKeepsTransBetasAndTheFaceWhicheverWayTheGraphWasBuilt) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string d = gmg::testing::shared_data_dir() + "/beat2_scott/";
  const std::string bvh = d + "2_scott_0_1_1.bvh", npz = d + "2_scott_0_1_1.npz";
  Config cfg;
  cfg.seed = 7;
  // The face along the body's path (face_mode=body); the face track of the new speech, the
  // default, is tests/pipeline/test_face_real_data.cpp's.
  cfg.face.mode = FaceMode::Body;
  const MotionGraph from_bvh =
      graph_build_from_files({{bvh, {d + "2_scott_0_1_1.wav", d + "2_scott_0_1_1.TextGrid"}}}, cfg);
  const MotionGraph from_npz =
      graph_build_from_files({{npz, {d + "2_scott_0_1_1.wav", d + "2_scott_0_1_1.TextGrid"}, bvh}}, cfg);
  EXPECT_FALSE(from_bvh.body.has_face());
  ASSERT_TRUE(from_npz.body.has_face());
  // The original file's arrays.
  const std::string original = read_file_bytes(npz);
  const ZipReader zo(original, npz);
  std::vector<double> trans_y;
  const NpyArray trans = npy_parse(zo.read("trans.npy"), "t");
  for (std::size_t i = 1; i < trans.values.size(); i += 3) trans_y.push_back(trans.values[i]);
  const NpyArray expressions = npy_parse(zo.read("expressions.npy"), "e");

  gmg::testing::TempDir tmp;
  for (const MotionGraph* g : {&from_bvh, &from_npz}) {
    const std::string which = g == &from_bvh ? "built from the BVH" : "built from the npz";
    const Reenactment r = reenact(*g, {d + "2_scott_0_2_2.wav", d + "2_scott_0_2_2.TextGrid"}, cfg, "g");
    const std::string out = tmp.file("out.npz");
    motion_write(out, r.motion, r.body);
    const std::string written = read_file_bytes(out);
    const ZipReader zw(written, out);
    // BEAT2's keys, in its order, with its dtypes and shapes (frames aside).
    EXPECT_EQ(zw.names(), zo.names()) << which;
    for (const std::string key : {"betas.npy", "poses.npy", "expressions.npy", "trans.npy", "mocap_frame_rate.npy"}) {
      const NpyArray a = npy_parse(zo.read(key), key), b = npy_parse(zw.read(key), key);
      EXPECT_EQ(b.dtype, a.dtype) << which << " " << key;
      ASSERT_EQ(b.shape.size(), a.shape.size()) << which << " " << key;
      for (std::size_t k = key == "betas.npy" || key == "mocap_frame_rate.npy" ? 0 : 1; k < a.shape.size(); ++k)
        EXPECT_EQ(b.shape[k], a.shape[k]) << which << " " << key;
    }
    // trans in BEAT2's convention: its median height within 1 cm of the real file's.
    const NpyArray t = npy_parse(zw.read("trans.npy"), "t");
    std::vector<double> y;
    for (std::size_t i = 1; i < t.values.size(); i += 3) y.push_back(t.values[i]);
    EXPECT_NEAR(median_of(y), median_of(trans_y), 0.01) << which;
    const NpyArray betas = npy_parse(zw.read("betas.npy"), "b");
    const nlohmann::ordered_json& body = r.report["body"];
    if (g == &from_bvh) {
      EXPECT_EQ(betas.values, std::vector<double>(300, 0.0));
      EXPECT_EQ(body["face"], "none");
      EXPECT_NE(body["note"].get<std::string>().find("the reference has no face"), std::string::npos);
      continue;
    }
    EXPECT_EQ(betas.values, npy_parse(zo.read("betas.npy"), "b").values);
    EXPECT_EQ(body["face"], "reference");
    EXPECT_EQ(body["betas"], "reference");
    // The face follows the motion: each output frame has the face of the source time it plays.
    // Before the first transition exactly; later, once a transition's offset has decayed.
    const NpyArray e = npy_parse(zw.read("expressions.npy"), "e");
    std::vector<char> continues(static_cast<std::size_t>(g->frame_count()));
    for (int f = 0; f < g->frame_count(); ++f)
      continues[static_cast<std::size_t>(f)] = !(g->node(f).kinds & kBreakNode);
    std::vector<PathPiece> pieces;
    for (const PlannedSegment& s : r.plan.segments) pieces.push_back({s.path, s.sub.length});
    const std::vector<SourceClock> clock = source_timeline(pieces, continues);
    ASSERT_EQ(clock.size(), static_cast<std::size_t>(r.motion.frame_count));
    // A transition's offset decays on the spring of transition_halflife: after 15 half-lives it
    // is below 1e-6 of the coefficients' range, after 4 below a tenth.
    const double halflife_frames = cfg.blend.halflife_s * g->motion.fps;
    int since = 0, first_run = 0, settled = 0;
    bool transition_seen = false;
    std::vector<double> error, shifted;
    for (std::size_t i = 0; i < clock.size(); ++i) {
      if (i > 0 && clock[i].run != clock[i - 1].run) {
        since = 0;
        transition_seen = true;
      }
      ++since;
      double worst = 0;
      for (int c = 0; c < 100; ++c)
        worst = std::max(worst, std::abs(e.values[i * 100 + static_cast<std::size_t>(c)] -
                                         value_at(expressions.values, 100, clock[i].time, c)));
      const double later = clock[i].time + 30.0;
      if (later < g->frame_count() - 1 && (!transition_seen || since > 4 * halflife_frames)) {
        double away = 0;
        for (int c = 0; c < 100; ++c)
          away = std::max(away, std::abs(e.values[i * 100 + static_cast<std::size_t>(c)] -
                                         value_at(expressions.values, 100, later, c)));
        error.push_back(worst);
        shifted.push_back(away);
      }
      if (!transition_seen) {
        EXPECT_LT(worst, 1e-12) << "frame " << i;
        ++first_run;
      } else if (since > 15 * halflife_frames) {
        EXPECT_LT(worst, 1e-6) << "frame " << i;
        ++settled;
      }
    }
    EXPECT_GT(first_run + settled, 0);
    ASSERT_FALSE(error.empty());
    // Wherever a transition's offset has mostly decayed (4 half-lives on), the face is nearer the
    // one it plays than the face a second later by far.
    EXPECT_LT(median_of(error), 0.25);
    EXPECT_GT(median_of(shifted), 5 * median_of(error));
    std::cout << "[ info ] face: " << first_run << " frames before the first transition, " << settled << " settled, "
              << error.size() << " decayed: median largest coefficient error " << median_of(error) << ", "
              << median_of(shifted) << " a second later\n";
  }
}

}  // namespace
}  // namespace gmg
