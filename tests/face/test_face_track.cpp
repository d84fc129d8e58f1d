// The face track: the jaw and expressions follow the new speech's phones (or its sound without
// phones), not the reference's clock, and stay inside the reference's expression range.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/face/face_track.h"
#include "engine/face/reference_speech.h"
#include "engine/motion/rotation.h"
#include "tests/face/synthetic_face.h"

namespace gmg {
namespace {

using namespace gmg::testing;

// The reference: 40 words of three phones in a fixed rotation, with their own lengths.
std::vector<text::Phone> reference_phones() {
  const std::vector<std::vector<std::string>> words = {{"M", "AA", "P"}, {"B", "AE", "M"}, {"S", "IY", "T"},
                                                       {"P", "AH", "N"}, {"N", "OW", "M"}, {"T", "AA", "B"}};
  std::vector<std::string> symbols;
  for (int w = 0; w < 40; ++w) {
    for (const std::string& s : words[static_cast<std::size_t>(w) % words.size()]) symbols.push_back(s);
    symbols.emplace_back("");
  }
  return phones_of(symbols, {4, 6, 5, 7, 3});
}

// New speech: other words, other lengths.
std::vector<text::Phone> new_phones() {
  const std::vector<std::vector<std::string>> words = {
      {"B", "AA", "M"}, {"P", "AE", "P"}, {"M", "AH", "B"}, {"T", "IY", "M"}, {"AA", "M"}};
  std::vector<std::string> symbols;
  for (int w = 0; w < 15; ++w) {
    for (const std::string& s : words[static_cast<std::size_t>(w) % words.size()]) symbols.push_back(s);
    symbols.emplace_back("");
  }
  return phones_of(symbols, {6, 9, 5, 8});
}

int frames_of(const std::vector<text::Phone>& phones) {
  return static_cast<int>(std::ceil(phones.back().end * kFps)) + 10;
}

struct Output {
  Motion motion;
  SmplxBody body;
  FaceTrack track;
};

FaceParams speech_params() {
  FaceParams p;
  p.mode = FaceMode::Speech;
  return p;
}

Output reenact_face(const MotionGraph& g, const std::vector<text::Phone>& phones, bool give_phones,
                    const FaceParams& params = speech_params()) {
  const int frames = frames_of(phones);
  Output out;
  out.motion = motion_rest(g.motion.skeleton, kFps, frames);
  out.body.expression_dims = 3;
  out.body.expressions.assign(static_cast<std::size_t>(frames) * 3, 7.0);  // what the body's path gave
  out.track = face_track(g, features_of(phones, frames), give_phones ? &phones : nullptr, frames, params);
  apply_face_track(g, out.track, out.motion, out.body);
  return out;
}

double jaw_angle(const Motion& m, int f) { return rotation_angle(m.rotation(f, 1)); }

// Frames well inside each phone of the new speech: a frame or more from its ends, where a
// cross-fade may reach.
template <typename Check>
void for_inner_frames(const std::vector<text::Phone>& phones, Check check) {
  for (const text::Phone& p : phones)
    for (int f = static_cast<int>(std::ceil(p.start * kFps + 1.0)); f <= p.end * kFps - 1.0; ++f) check(p.symbol, f);
}

TEST(FaceTrack, TheJawOpensOnTheNewSpeechsVowelsAndClosesOnItsBilabials) {
  const std::vector<text::Phone> ref = reference_phones();
  const MotionGraph g = face_graph(ref, frames_of(ref));
  const std::vector<text::Phone> speech = new_phones();
  const Output out = reenact_face(g, speech, true);
  ASSERT_EQ(out.track.follows, "speech");
  EXPECT_TRUE(out.track.from_phones);
  int open = 0, closed = 0;
  for_inner_frames(speech, [&](const std::string& symbol, int f) {
    const double jaw = jaw_angle(out.motion, f), e0 = out.body.expressions[static_cast<std::size_t>(f) * 3];
    if (text::viseme_of(symbol) == text::Viseme::OpenVowel) {
      ++open;
      EXPECT_NEAR(jaw, kOpen, 1e-6) << symbol << " at frame " << f;
      EXPECT_NEAR(e0, kOpen, 1e-6) << symbol << " at frame " << f;
    } else if (text::viseme_of(symbol) == text::Viseme::Bilabial) {
      ++closed;
      EXPECT_NEAR(jaw, kClosed, 1e-6) << symbol << " at frame " << f;
      EXPECT_NEAR(e0, kClosed, 1e-6) << symbol << " at frame " << f;
    }
  });
  EXPECT_GT(open, 60);
  EXPECT_GT(closed, 60);
  // The reference's clock would give other faces: the same frames of the reference hold other phones.
  int differ = 0;
  for_inner_frames(speech, [&](const std::string& symbol, int f) {
    differ += text::viseme_of(symbol_at(ref, f)) != text::viseme_of(symbol);
  });
  EXPECT_GT(differ, 100);
}

TEST(FaceTrack, EveryExpressionStaysInsideTheReferencesRange) {
  const std::vector<text::Phone> ref = reference_phones();
  const MotionGraph g = face_graph(ref, frames_of(ref));
  for (const bool phones : {true, false}) {
    FaceParams p = speech_params();
    p.crossfade_s = 0.2;  // long cross-fades: many blended frames
    const Output out = reenact_face(g, new_phones(), phones, p);
    ASSERT_EQ(out.track.follows, "speech");
    for (int d = 0; d < 3; ++d) {
      double lo = 1e9, hi = -1e9;
      for (int f = 0; f < g.frame_count(); ++f) {
        lo = std::min(lo, g.body.expressions[static_cast<std::size_t>(f) * 3 + d]);
        hi = std::max(hi, g.body.expressions[static_cast<std::size_t>(f) * 3 + d]);
      }
      for (std::size_t f = 0; f < out.body.expressions.size() / 3; ++f) {
        const double e = out.body.expressions[f * 3 + static_cast<std::size_t>(d)];
        EXPECT_GE(e, lo - 1e-12) << "dimension " << d << " frame " << f;
        EXPECT_LE(e, hi + 1e-12) << "dimension " << d << " frame " << f;
      }
    }
  }
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const auto n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

TEST(FaceTrack, WithoutPhonesTheJawFollowsTheSpeechsSound) {
  const std::vector<text::Phone> ref = reference_phones();
  for (const bool reference_phones_known : {true, false}) {
    const MotionGraph g = face_graph(ref, frames_of(ref), reference_phones_known);
    const std::vector<text::Phone> speech = new_phones();
    const Output out = reenact_face(g, speech, false);
    ASSERT_EQ(out.track.follows, "speech");
    EXPECT_FALSE(out.track.from_phones);
    EXPECT_EQ(face_track_report(out.track)["units"], "audio windows");
    std::vector<double> jaw, wanted;
    for (int f = 0; f < out.motion.frame_count; ++f) {
      jaw.push_back(jaw_angle(out.motion, f));
      wanted.push_back(jaw_of(symbol_at(speech, f)));
    }
    EXPECT_GT(correlation(jaw, wanted), 0.8) << "reference phones known: " << reference_phones_known;
  }
}

TEST(FaceTrack, FollowsTheBodyWhenAskedOrWhenTheGraphCannotSayMore) {
  const std::vector<text::Phone> ref = reference_phones();
  MotionGraph g = face_graph(ref, frames_of(ref));
  FaceParams body;
  body.mode = FaceMode::Body;
  Output out = reenact_face(g, new_phones(), true, body);
  EXPECT_EQ(out.track.follows, "body");
  EXPECT_EQ(out.track.why, "face_mode=body");
  EXPECT_TRUE(std::all_of(out.body.expressions.begin(), out.body.expressions.end(), [](double e) { return e == 7.0; }));
  EXPECT_EQ(jaw_angle(out.motion, 20), 0.0);

  out = reenact_face(g, new_phones(), true);  // the default: the track of the new speech
  EXPECT_EQ(out.track.follows, "speech");

  g.face_speech = FaceSpeech();  // a graph of format 11
  out = reenact_face(g, new_phones(), true);
  EXPECT_EQ(out.track.follows, "body");
  EXPECT_NE(out.track.why.find("older gmg"), std::string::npos) << out.track.why;

  MotionGraph bvh = face_graph(ref, frames_of(ref));
  bvh.body = SmplxBody();
  bvh.motion.skeleton.joints[1].name = "head";
  EXPECT_EQ(face_track_unavailable(bvh), "the reference has no face (no expressions and no jaw joint)");

  // What `gmg inspect` says of each.
  const MotionGraph full = face_graph(ref, frames_of(ref));
  EXPECT_EQ(face_track_summary(full),
            "the new speech: " + std::to_string(full.body.expression_dims) + " expressions, the jaw, by phones (" +
                std::to_string(full.face_speech.phones.size()) + " reference phones) and sound");
  EXPECT_EQ(face_track_summary(face_graph(ref, frames_of(ref), false)).substr(0, 16), "the new speech: ");
  EXPECT_NE(face_track_summary(face_graph(ref, frames_of(ref), false)).find("by sound only"), std::string::npos);
  EXPECT_EQ(face_track_summary(g),
            "along the body (the graph keeps no face speech (built by an older gmg: rebuild it))");
  EXPECT_EQ(face_track_summary(bvh), "none (the reference has no face (no expressions and no jaw joint))");
}

TEST(FaceTrack, ItsParametersAreCheckedWithTheirRanges) {
  const std::vector<text::Phone> ref = reference_phones();
  const MotionGraph g = face_graph(ref, frames_of(ref));
  FaceParams p = speech_params();
  p.candidates = 0;
  EXPECT_THROW(reenact_face(g, new_phones(), true, p), Error);
  p = FaceParams();
  p.crossfade_s = 2.0;
  try {
    face_params_validate(p);
    ADD_FAILURE() << "accepted crossfade 2 s";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("face_crossfade_s must be in [0, 1]"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gmg
