// The face track on BEAT2 speaker scott (graph of 2_scott_0_1_1.npz with its TextGrid), new speech
// 0_2_2 and 0_3_3: the jaw follows the new speech's loudness and phones as the reference's follows
// its own, the expressions stay inside the reference's range, and the body is the one face_mode=body
// gives with the same seed. The figures' definitions: engine/metrics/face_metrics.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "audio/wav.h"
#include "engine/metrics/face_metrics.h"
#include "engine/motion/body_parts.h"
#include "engine/pipeline/pipeline.h"
#include "tests/test_support.h"
#include "text/phones.h"

namespace gmg {
namespace {

std::vector<MouthSpan> mouth_of(const std::string& textgrid) {
  std::vector<MouthSpan> out;
  for (const text::Phone& p : text::read_phones(textgrid)) {
    const text::Viseme v = text::viseme_of(p.symbol);
    if (v == text::Viseme::OpenVowel || v == text::Viseme::Bilabial)
      out.push_back({p.start, p.end, v == text::Viseme::OpenVowel});
  }
  return out;
}

double jaw_energy(const Motion& m, const std::string& wav) {
  const std::optional<double> c =
      jaw_energy_correlation(jaw_angles(m), frame_rms(audio::read_wav(wav), m.fps, m.frame_count));
  EXPECT_TRUE(c.has_value()) << wav;
  return c.value_or(0.0);
}

TEST(FaceRealData, TheFaceTrackSpeaksTheNewSpeechAndLeavesTheBodyAsItWas) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string d = gmg::testing::shared_data_dir() + "/beat2_scott/";
  const std::string own = d + "2_scott_0_1_1";
  Config speech;
  speech.seed = 1;
  ASSERT_EQ(speech.face.mode, FaceMode::Speech);  // the default
  Config body = speech;
  body.face.mode = FaceMode::Body;
  const MotionGraph g =
      graph_build_from_files({{own + ".npz", {own + ".wav", own + ".TextGrid"}, own + ".bvh"}}, speech);
  ASSERT_TRUE(g.body.has_face());
  const int jaw = jaw_joint(g.motion.skeleton);
  ASSERT_GE(jaw, 0);

  // The reference with its own speech: what the outputs are measured against.
  const double ref_energy = jaw_energy(g.motion, own + ".wav");
  const std::optional<double> ref_contrast = viseme_contrast(jaw_angles(g.motion), mouth_of(own + ".TextGrid"), 30.0);
  ASSERT_TRUE(ref_contrast.has_value());
  std::cout << "[ info ] reference: jaw-energy " << ref_energy << ", viseme contrast " << *ref_contrast << "\n";
  ASSERT_GT(ref_energy, 0.2);
  ASSERT_GT(*ref_contrast, 2.0);

  const std::vector<std::string> tests = {d + "2_scott_0_2_2", d + "2_scott_0_3_3"};
  for (std::size_t t = 0; t < tests.size(); ++t) {
    const std::string& test = tests[t];
    const std::string& other = tests[1 - t];
    const Reenactment r = reenact(g, {test + ".wav", test + ".TextGrid"}, speech, "scott");
    ASSERT_EQ(r.report["face_track"]["follows"], "speech") << r.report["face_track"].dump();
    EXPECT_EQ(r.report["face_track"]["units"], "phones");

    // The jaw follows this speech, not any speech: matched against the mismatched control.
    const double matched = jaw_energy(r.motion, test + ".wav");
    const double mismatched = jaw_energy(r.motion, other + ".wav");
    const std::optional<double> contrast = viseme_contrast(jaw_angles(r.motion), mouth_of(test + ".TextGrid"), 30.0);
    ASSERT_TRUE(contrast.has_value());
    const double out_of_range =
        expressions_out_of_range(r.body.expressions, g.body.expressions, g.body.expression_dims, 0.05);
    std::cout << "[ info ] " << test << ": jaw-energy " << matched << " (mismatched " << mismatched
              << "), viseme contrast " << *contrast << ", expressions out of range " << out_of_range << "\n";
    EXPECT_GE(matched, 0.7 * ref_energy) << test;
    EXPECT_GT(matched - mismatched, 0.15) << test;
    EXPECT_GE(*contrast, 0.7 * *ref_contrast) << test;
    EXPECT_LE(out_of_range, 0.01) << test;

    // The body is face_mode=body's with the same seed: every joint but the jaw, and the root.
    const Reenactment b = reenact(g, {test + ".wav", test + ".TextGrid"}, body, "scott");
    ASSERT_EQ(b.motion.frame_count, r.motion.frame_count);
    EXPECT_EQ(b.motion.translations, r.motion.translations);
    const std::size_t joints = g.motion.skeleton.joints.size();
    int differ = 0;
    for (int f = 0; f < r.motion.frame_count; ++f)
      for (std::size_t j = 0; j < joints; ++j)
        if (static_cast<int>(j) != jaw &&
            r.motion.rotation(f, static_cast<int>(j)) != b.motion.rotation(f, static_cast<int>(j)))
          ++differ;
    EXPECT_EQ(differ, 0) << test;
    EXPECT_NE(jaw_energy(b.motion, test + ".wav"), matched);  // the control: the jaw is another one

    // Audio alone (no transcript): the track cuts the speech into windows and follows its sound.
    const Reenactment a = reenact(g, {test + ".wav", ""}, speech, "scott");
    EXPECT_EQ(a.report["face_track"]["units"], "audio windows");
    const double audio_only = jaw_energy(a.motion, test + ".wav");
    std::cout << "[ info ] " << test << " audio only: jaw-energy " << audio_only << "\n";
    EXPECT_GE(audio_only, 0.6 * ref_energy) << test;
    EXPECT_LE(expressions_out_of_range(a.body.expressions, g.body.expressions, g.body.expression_dims, 0.05), 0.01);
  }
}

}  // namespace
}  // namespace gmg
