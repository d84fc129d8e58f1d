// Tests of the synthetic speaker's motion (engine/synth): a person standing and talking. Planted
// feet and slightly bent knees, weight shifts, beats on stressed syllables, larger gestures on
// keywords, hands at rest between sentences, no jumps. Every figure is measured on the joints'
// world positions (forward kinematics), not on the curves the generator draws from.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/core/math.h"
#include "engine/motion/bvh.h"
#include "engine/motion/motion.h"
#include "engine/synth/synth.h"
#include "graph/breaks.h"
#include "graph/features.h"
#include "tests/test_support.h"

namespace {

using gmg::SynthClip;
using gmg::SynthSpec;

SynthSpec spec_of(double duration, std::uint64_t seed, double style = 0.0) {
  SynthSpec s;
  s.duration_s = duration;
  s.seed = seed;
  s.style = style;
  return s;
}

// World positions of a clip, by joint name.
struct Positions {
  Eigen::MatrixXd p;
  const gmg::Skeleton& sk;
  Positions(const gmg::Motion& m) : p(gmg::motion_forward_kinematics(m)), sk(m.skeleton) {}
  glm::dvec3 at(int f, const char* name) const {
    const Eigen::Index j = sk.find(name);
    EXPECT_GE(j, 0) << name;
    return {p(f, 3 * j), p(f, 3 * j + 1), p(f, 3 * j + 2)};
  }
};

// The angle (degrees) between the thigh (hip -> knee) and the shin (knee -> ankle): 0 straight.
double knee_bend(const Positions& p, int f, const std::string& side) {
  const glm::dvec3 hip = p.at(f, (side + "UpLeg").c_str()), knee = p.at(f, (side + "Leg").c_str());
  const glm::dvec3 ankle = p.at(f, (side + "Foot").c_str());
  const double c = glm::dot(glm::normalize(knee - hip), glm::normalize(ankle - knee));
  return std::acos(std::clamp(c, -1.0, 1.0)) / gmg::kDegToRad;
}

// The largest distance between two positions of `joint` over frames [f0, f1].
double extent(const Positions& p, const char* joint, int f0, int f1) {
  double best = 0;
  for (int a = f0; a <= f1; ++a)
    for (int b = a + 1; b <= f1; ++b) best = std::max(best, glm::length(p.at(a, joint) - p.at(b, joint)));
  return best;
}

int frame_at(double t, const gmg::Motion& m) {
  return std::clamp(static_cast<int>(std::lround(t * m.fps)), 0, m.frame_count - 1);
}

// ---------------------------------------------------------------------------------------------

TEST(SynthBody, FeetStayPlantedOnTheFloorAndKneesAreSlightlyBent) {
  for (double style : {0.0, 1.0}) {
    SCOPED_TRACE(style);
    const SynthClip clip = gmg::synth_speaker(spec_of(60.0, 5, style));
    const Positions p(clip.motion);
    double drift = 0, lowest = 1e9, highest = -1e9, bend_lo = 180, bend_hi = 0;
    double bend_range[2] = {0, 0};
    for (const std::string side : {"Left", "Right"}) {
      const glm::dvec3 ankle0 = p.at(0, (side + "Foot").c_str()), toe0 = p.at(0, (side + "ToeBase").c_str());
      double lo = 180, hi = 0;
      for (int f = 0; f < clip.motion.frame_count; ++f) {
        drift = std::max(drift, glm::length(p.at(f, (side + "Foot").c_str()) - ankle0));
        drift = std::max(drift, glm::length(p.at(f, (side + "ToeBase").c_str()) - toe0));
        lowest = std::min(lowest, p.at(f, (side + "ToeBase").c_str()).y);
        highest = std::max(highest, p.at(f, (side + "ToeBase").c_str()).y);
        const double b = knee_bend(p, f, side);
        lo = std::min(lo, b);
        hi = std::max(hi, b);
      }
      bend_lo = std::min(bend_lo, lo);
      bend_hi = std::max(bend_hi, hi);
      bend_range[side == "Left" ? 0 : 1] = hi - lo;
    }
    std::printf("style %.0f: feet moved at most %.2g cm, toes at height %.3g..%.3g cm, knees bent %.1f..%.1f deg\n",
                style, drift, lowest, highest, bend_lo, bend_hi);
    EXPECT_LT(drift, 1e-6);          // planted: the same place at every frame
    EXPECT_NEAR(lowest, 0.0, 1e-6);  // on the floor
    EXPECT_NEAR(highest, 0.0, 1e-6);
    // A standing person's knees: never locked straight, never crouching.
    EXPECT_GE(bend_lo, 5.0);
    EXPECT_LE(bend_hi, 20.0);
    // Each knee relaxes and straightens as the weight moves.
    EXPECT_GT(bend_range[0], 6.0);
    EXPECT_GT(bend_range[1], 6.0);
  }
}

TEST(SynthBody, WeightShiftsEveryFewSeconds) {
  const SynthClip clip = gmg::synth_speaker(spec_of(60.0, 8));
  const Positions p(clip.motion);
  // The hips over one foot, the other, or between: count the times the hips cross from one
  // side (x beyond +-1.5 cm of the middle of the feet) to the other.
  const double middle = 0.5 * (p.at(0, "LeftFoot").x + p.at(0, "RightFoot").x);
  int side = 0, crossings = 0;
  double lo = 1e9, hi = -1e9;
  for (int f = 0; f < clip.motion.frame_count; ++f) {
    const double x = p.at(f, "Hips").x - middle;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
    const int now = x > 1.5 ? 1 : (x < -1.5 ? -1 : 0);
    if (now != 0 && now != side) {
      if (side != 0) ++crossings;
      side = now;
    }
  }
  std::printf("60 s: hips sway %.1f..%.1f cm about the feet's middle, %d crossings\n", lo, hi, crossings);
  EXPECT_GT(hi - lo, 4.0);
  EXPECT_GE(crossings, 3);  // every few seconds, not once
  EXPECT_LE(crossings, 20);
}

TEST(SynthBody, HandsRestBetweenSentences) {
  const SynthClip clip = gmg::synth_speaker(spec_of(90.0, 3));
  const gmg::Motion& m = clip.motion;
  const Positions p(m);
  int long_pauses = 0;
  for (std::size_t k = 0; k + 1 < clip.phrases.size(); ++k) {
    if (!clip.phrases[k].ends_sentence) continue;
    // The middle of a pause of 2 s or so: the hands have sunk and not yet risen.
    const double a = clip.phrases[k].end + 0.95, b = clip.phrases[k + 1].start - 0.95;
    if (b - a < 0.1) continue;
    ++long_pauses;
    for (int f = frame_at(a, m); f <= frame_at(b, m); ++f)
      for (const char* hand : {"LeftHand", "RightHand"}) {
        // Beside the thighs: below the hips, within 30 cm of the body's middle.
        EXPECT_LT(p.at(f, hand).y, p.at(f, "Hips").y) << hand << " at " << f / m.fps << " s";
        EXPECT_LT(std::abs(p.at(f, hand).x - p.at(f, "Hips").x), 30.0) << hand;
        if (f > 0) {
          EXPECT_LT(glm::length(p.at(f, hand) - p.at(f - 1, hand)), 0.3) << hand << " moves at rest";
        }
      }
  }
  EXPECT_GE(long_pauses, 3);
  // While speaking the hands are up in front of the body: above the hips, forward of them.
  int speaking = 0, up = 0;
  for (const gmg::SynthPhrase& ph : clip.phrases)
    for (int f = frame_at(ph.start, m); f <= frame_at(ph.end, m); ++f) {
      ++speaking;
      const glm::dvec3 hand = p.at(f, "RightHand"), hips = p.at(f, "Hips");
      if (hand.y > hips.y + 10.0 && hand.z > hips.z + 15.0) ++up;
    }
  std::printf("right hand up in front while speaking: %d of %d frames\n", up, speaking);
  EXPECT_GT(up, 0.9 * speaking);
}

TEST(SynthBody, BeatsOnStressesAndLargerGesturesOnKeywords) {
  for (double style : {0.0, 1.0}) {
    SCOPED_TRACE(style);
    const SynthClip clip = gmg::synth_speaker(spec_of(60.0, 21, style));
    const gmg::Motion& m = clip.motion;
    const Positions p(m);
    // The dominant hand's speed near stressed syllables (within 0.15 s) against the rest of the
    // speech (phrases), frames near a keyword left out of both.
    std::vector<char> near(static_cast<std::size_t>(m.frame_count), 0), keyword(near.size(), 0), speech(near.size(), 0);
    for (double kt : clip.keyword_times)
      for (int f = frame_at(kt - 0.4, m); f <= frame_at(kt + 1.0, m); ++f) keyword[static_cast<std::size_t>(f)] = 1;
    for (const gmg::SynthSyllable& syl : clip.syllables)
      if (syl.stressed)
        for (int f = frame_at(syl.time - 0.15, m); f <= frame_at(syl.time + 0.15, m); ++f)
          near[static_cast<std::size_t>(f)] = 1;
    for (const gmg::SynthPhrase& ph : clip.phrases)
      for (int f = frame_at(ph.start, m); f <= frame_at(ph.end, m); ++f) speech[static_cast<std::size_t>(f)] = 1;
    double sn = 0, so = 0;
    int nn = 0, no = 0;
    for (int f = 1; f < m.frame_count; ++f) {
      const auto i = static_cast<std::size_t>(f);
      if (keyword[i] || !speech[i]) continue;
      const double v = glm::length(p.at(f, "RightHand") - p.at(f - 1, "RightHand"));
      if (near[i])
        sn += v, ++nn;
      else
        so += v, ++no;
    }
    ASSERT_GT(nn, 0);
    ASSERT_GT(no, 0);
    // The extent of the dominant hand's movement around each beat and each keyword gesture.
    double beat_extent = 0, keyword_extent = 0;
    int beats = 0;
    for (const gmg::SynthSyllable& syl : clip.syllables) {
      const auto f = static_cast<std::size_t>(frame_at(syl.time, m));
      if (!syl.stressed || keyword[f]) continue;
      beat_extent += extent(p, "RightHand", frame_at(syl.time - 0.2, m), frame_at(syl.time + 0.2, m));
      ++beats;
    }
    for (double kt : clip.keyword_times)
      keyword_extent += extent(p, "RightHand", frame_at(kt - 0.35, m), frame_at(kt + 0.3, m));
    ASSERT_GT(beats, 10);
    ASSERT_GT(clip.keyword_times.size(), 5u);
    beat_extent /= beats;
    keyword_extent /= static_cast<double>(clip.keyword_times.size());
    std::printf(
        "style %.0f: right hand %.2f cm/frame near stresses, %.2f elsewhere in speech; moves %.1f cm in a beat, "
        "%.1f cm in a keyword gesture\n",
        style, sn / nn, so / no, beat_extent, keyword_extent);
    EXPECT_GT(sn / nn, 1.3 * (so / no));
    EXPECT_GT(beat_extent, 5.0);  // visible
    EXPECT_GT(keyword_extent, 2.0 * beat_extent);
  }
}

TEST(SynthBody, NoJumps) {
  for (double style : {0.0, 1.0}) {
    SCOPED_TRACE(style);
    SynthSpec s = spec_of(40.0, 21, style);
    s.joint_count_hint = 60;  // fingers too
    const SynthClip clip = gmg::synth_speaker(s);
    const gmg::Motion& m = clip.motion;
    const Eigen::MatrixXd p = gmg::motion_forward_kinematics(m);
    // Per joint: the largest step between frames (speed), and how much larger a step of 1 cm or
    // more is than the larger of its neighbours. In smooth motion steps grow and shrink from
    // frame to frame by a few tens of percent; a jump is one step several times its neighbours.
    double step = 0, ratio = 0;
    for (Eigen::Index j = 0; j < m.joint_count(); ++j) {
      std::vector<double> v(static_cast<std::size_t>(m.frame_count), 0.0);
      for (int f = 1; f < m.frame_count; ++f)
        v[static_cast<std::size_t>(f)] = (p.block(f, 3 * j, 1, 3) - p.block(f - 1, 3 * j, 1, 3)).norm();
      for (std::size_t f = 2; f + 1 < v.size(); ++f) {
        step = std::max(step, v[f]);
        if (v[f] >= 1.0) ratio = std::max(ratio, v[f] / std::max(v[f - 1], v[f + 1]));
      }
    }
    std::printf("style %.0f: largest step %.2f cm/frame, at most %.2f times a neighbouring step\n", style, step, ratio);
    EXPECT_LT(step, 12.0);  // 3.6 m/s: a fingertip in a fast stroke, not a jump
    EXPECT_LT(ratio, 2.0);
  }
}

// The graph's capture-jump detector (a frame step above 8 times the clip's median) finds none in
// short clips too, where a sentence's preparation from rest is the fastest thing: a graph of
// the speaker has break nodes only where its clips end.
TEST(SynthBody, NoCaptureJumpsForTheGraph) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const SynthClip clip = gmg::synth_speaker(spec_of(6.0, seed));
    EXPECT_TRUE(gmg::capture_jump_frames(gmg::pose_features(clip.motion), gmg::GraphParams{}).empty()) << seed;
  }
}

}  // namespace
