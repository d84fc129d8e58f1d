// Extra per-frame channels (an SMPL-X reference's face) along an assembly: they must be read at
// the source time each output frame plays and blended through transitions exactly as the
// motion's translations are. The checks compare against the motion's own assembly (a channel
// that holds the root's height must come out as the output root's height, bit for bit) and
// against the clock, not against a second implementation.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/assemble/blend.h"
#include "engine/assemble/channels.h"
#include "engine/assemble/resample.h"
#include "engine/assemble/timeline.h"
#include "engine/assemble/transitions.h"
#include "engine/core/enum_names.h"
#include "engine/core/error.h"
#include "engine/synth/synth.h"

namespace gmg {
namespace {

// A synthetic capture of 600 frames (the root sways and breathes, so its height moves) with a
// capture break after frame 299.
struct Source {
  Motion motion;
  std::vector<char> continues;
};

Source source() {
  SynthSpec spec;
  spec.duration_s = 20;
  spec.seed = 31;
  Source s{synth_speaker(spec).motion, {}};
  s.continues.assign(static_cast<std::size_t>(s.motion.frame_count), 1);
  s.continues[299] = 0;
  s.continues.back() = 0;
  return s;
}

// Pieces with everything a plan has: a natural run, a jump into another stretch, a stretched and a
// squeezed piece, a path that crosses the break, a held frame.
std::vector<PathPiece> pieces() {
  auto run = [](int first, int n, int length) {
    PathPiece p;
    for (int f = first; f < first + n; ++f) p.path.push_back(f);
    p.length = length;
    return p;
  };
  std::vector<PathPiece> out = {run(10, 40, 40), run(50, 30, 30), run(400, 30, 45), run(120, 60, 40)};
  PathPiece cross = run(290, 10, 10);
  for (int f = 450; f < 470; ++f) cross.path.push_back(f);
  cross.length = 30;
  out.push_back(cross);
  out.push_back({{200}, 12});
  out.push_back(run(500, 80, 80));
  return out;
}

// Channels per source frame: the root's height, the frame number, then both again transformed
// (a channel count that is not a multiple of three).
std::vector<double> channels_of(const Motion& m, int& dims) {
  dims = 4;
  std::vector<double> v;
  for (int f = 0; f < m.frame_count; ++f) {
    const double y = m.translation(f, 0).y;
    v.insert(v.end(), {y, static_cast<double>(f), 2.0 * y + 1.0, -static_cast<double>(f)});
  }
  return v;
}

TEST(Channels, AChannelIsInertializedExactlyLikeATranslationOnTheMotionsClock) {
  const Source s = source();
  BlendParams params;  // the defaults: inertialize, root anchor, foot lock
  const Motion out = assemble_inertialized(s.motion, s.continues, pieces(), params);
  int dims = 0;
  const std::vector<double> values = channels_of(s.motion, dims);
  const std::vector<double> ch =
      assemble_channels_inertialized(values, dims, s.continues, pieces(), params.halflife_s * s.motion.fps);
  ASSERT_EQ(ch.size(), static_cast<std::size_t>(out.frame_count) * 4);
  const std::vector<SourceClock> clock = source_timeline(pieces(), s.continues);
  int transitions = 0;
  for (int i = 0; i < out.frame_count; ++i) {
    const double* c = &ch[static_cast<std::size_t>(i) * 4];
    // The root's height is a translation the anchor leaves alone: the channel holding it is
    // assembled into the output root's height, bit for bit.
    EXPECT_EQ(c[0], out.translation(i, 0).y) << "frame " << i;
    // Linear in the channel: the transformed copies follow (to rounding).
    EXPECT_NEAR(c[2], 2.0 * c[0] + 1.0, 1e-12) << "frame " << i;
    EXPECT_NEAR(c[3], -c[1], 1e-9) << "frame " << i;
    transitions += i > 0 && clock[static_cast<std::size_t>(i)].run != clock[static_cast<std::size_t>(i - 1)].run;
    // Before the first transition nothing is blended: the frame number is the source time played.
    if (transitions == 0) {
      EXPECT_NEAR(c[1], clock[static_cast<std::size_t>(i)].time, 1e-12) << "frame " << i;
    }
  }
  EXPECT_GE(transitions, 4);
}

TEST(Channels, AfterATransitionTheChannelSettlesOnTheSourceItPlays) {
  // One jump (frame 100 -> 400), then 300 frames of the new stretch: the offset decays and the
  // frame-number channel ends on the source time, as a translation does.
  const Source s = source();
  std::vector<PathPiece> p(2);
  for (int f = 0; f <= 100; ++f) p[0].path.push_back(f);
  p[0].length = 101;
  for (int f = 400; f < 580; ++f) p[1].path.push_back(f);
  p[1].length = 180;
  int dims = 0;
  const std::vector<double> values = channels_of(s.motion, dims);
  const std::vector<double> ch = assemble_channels_inertialized(values, dims, s.continues, p, 6.0);
  const std::vector<SourceClock> clock = source_timeline(p, s.continues);
  const double jump = 400 - 101;             // where the old source was heading, and where the new one is
  EXPECT_NEAR(ch[101 * 4 + 1], 101.0, 1.5);  // continuous at the switch: still near the old stretch
  EXPECT_GT(std::abs(ch[120 * 4 + 1] - clock[120].time), 1.0);  // still blending
  for (int i = 230; i < 281; ++i)
    EXPECT_NEAR(ch[static_cast<std::size_t>(i) * 4 + 1], clock[static_cast<std::size_t>(i)].time, 1e-6 * jump) << i;
}

TEST(Channels, ThePapersBlendingJoinsChannelsAsItJoinsTranslations) {
  const Source s = source();
  for (BlendMode mode : {BlendMode::Offset, BlendMode::Crossfade}) {
    BlendParams params;
    params.mode = mode;
    params.root = RootMode::Free;
    std::vector<Motion> resampled;
    for (const PathPiece& piece : pieces()) resampled.push_back(resample_path(s.motion, piece.path, piece.length));
    const Motion out = blend_concatenate(resampled, params);
    int dims = 0;
    const std::vector<double> values = channels_of(s.motion, dims);
    const std::vector<double> ch = assemble_channels_blended(values, dims, pieces(), params);
    ASSERT_EQ(ch.size(), static_cast<std::size_t>(out.frame_count) * 4);
    for (int i = 0; i < out.frame_count; ++i)
      EXPECT_EQ(ch[static_cast<std::size_t>(i) * 4], out.translation(i, 0).y)
          << enum_name(kBlendModeNames, mode) << " " << i;
  }
}

TEST(Channels, ChannelsThatDoNotCoverTheSourceAreRefused) {
  const Source s = source();
  EXPECT_THROW(assemble_channels_inertialized(std::vector<double>(10, 0.0), 4, s.continues, pieces(), 6.0), Error);
  EXPECT_THROW(assemble_channels_inertialized(std::vector<double>(2400, 0.0), 0, s.continues, pieces(), 6.0), Error);
}

}  // namespace
}  // namespace gmg
