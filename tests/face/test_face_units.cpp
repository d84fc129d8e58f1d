// Units of new speech (phones, silences, windows), the selection's joins and the warp's cross-fades.
#include <gtest/gtest.h>

#include "engine/face/reference_face.h"
#include "engine/face/selection.h"
#include "engine/face/units.h"
#include "engine/face/warp.h"
#include "tests/face/synthetic_face.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(FaceUnits, PhonesSilencesAndLongPausesAsWindows) {
  // Phones at 30 fps: frames 3-9 "M", 9-15 "AA", a pause of 6 frames, 21-24 "P", then a pause of
  // 30 frames (1 s, over silence_unit_max_s 0.4) to the end at 54.
  const std::vector<text::Phone> phones = {{0.1, 0.3, "M"}, {0.3, 0.5, "AA"}, {0.7, 0.8, "P"}};
  FaceParams p;
  const std::vector<FaceUnit> u = face_units(&phones, 30.0, 54, p);
  ASSERT_EQ(u.size(), 13u);
  EXPECT_DOUBLE_EQ(u[0].start, 0.0);  // the silence before the first phone
  EXPECT_DOUBLE_EQ(u[0].end, 3.0);
  EXPECT_TRUE(u[0].phone);
  EXPECT_EQ(u[0].symbol, "");
  EXPECT_EQ(u[1].symbol, "M");
  EXPECT_EQ(u[1].left, "");
  EXPECT_EQ(u[1].right, "AA");
  EXPECT_EQ(u[2].symbol, "AA");
  EXPECT_EQ(u[2].left, "M");
  EXPECT_EQ(u[2].right, "");
  EXPECT_DOUBLE_EQ(u[3].start, 15.0);  // the short pause: one silence unit
  EXPECT_DOUBLE_EQ(u[3].end, 21.0);
  EXPECT_EQ(u[4].symbol, "P");
  EXPECT_EQ(u[4].right, "");  // a window follows
  // The pause of 30 frames: windows of 4 frames, the remainder of 2 (half a window) its own.
  for (std::size_t i = 5; i < 12; ++i) {
    EXPECT_FALSE(u[i].phone);
    EXPECT_DOUBLE_EQ(u[i].end - u[i].start, 4.0);
  }
  EXPECT_DOUBLE_EQ(u[12].end, 54.0);
  EXPECT_DOUBLE_EQ(u[12].end - u[12].start, 2.0);

  const std::vector<FaceUnit> w = face_units(nullptr, 30.0, 9, p);
  ASSERT_EQ(w.size(), 2u);  // 4 + 5: a remainder under half a window joins the last one
  EXPECT_DOUBLE_EQ(w[1].start, 4.0);
  EXPECT_DOUBLE_EQ(w[1].end, 9.0);
}

TEST(FaceSelection, StretchesThatGoOnInTheReferenceJoinForFree) {
  const std::vector<text::Phone> phones = phones_of({"M", "AA", "P", "", "B", "AE", "M"}, {6});
  const MotionGraph g = face_graph(phones, 60);
  const ReferenceFace r = reference_face(g);
  FaceParams p;
  p.join_weight = 1.0;
  p.join_cost = 0.5;
  const FaceCandidate a{10.0, 16.0, 0, 0.0}, on{16.0, 22.0, 0, 0.0}, away{40.0, 46.0, 0, 0.0};
  EXPECT_EQ(face_join_cost(r, a, on, p), 0.0);
  // Elsewhere: join_cost plus the faces' difference (frame 15 against frame 40, both "AA"-less).
  EXPECT_NEAR(face_join_cost(r, a, away, p), p.join_weight * (r.face_distance(15, 40) + p.join_cost), 1e-12);
  // Two units whose cheapest candidates by target cost are apart, and a pair that goes on at a
  // little more target cost: the selection takes the pair.
  std::vector<std::vector<FaceCandidate>> c = {{{10.0, 16.0, 0, 0.0}, {30.0, 36.0, 0, 0.05}},
                                               {{40.0, 46.0, 0, 0.0}, {36.0, 42.0, 0, 0.1}}};
  const std::vector<int> chosen = select_face_stretches(r, c, p);
  EXPECT_EQ(chosen, (std::vector<int>{1, 1}));
}

TEST(FaceWarp, EachUnitIsWarpedOntoItsLengthAndCutsAreCrossFaded) {
  const std::vector<text::Phone> phones = phones_of({"M", "AA", "P"}, {6});
  const MotionGraph g = face_graph(phones, 60);
  const ReferenceFace r = reference_face(g);
  std::vector<FaceUnit> units(2);
  units[0].start = 0.0;
  units[0].end = 4.0;
  units[1].start = 4.0;
  units[1].end = 12.0;
  // Unit 0 plays reference 10-18 (twice as fast), unit 1 reference 30-34 (half as fast).
  const std::vector<FaceCandidate> chosen = {{10.0, 18.0, 0, 0.0}, {30.0, 34.0, 0, 0.0}};
  const std::vector<FaceSource> s = face_sources(r, units, chosen, 12, 1.5);
  ASSERT_EQ(s.size(), 12u);
  EXPECT_DOUBLE_EQ(s[0].a, 10.0);
  EXPECT_DOUBLE_EQ(s[0].w, 0.0);
  EXPECT_DOUBLE_EQ(s[1].a, 12.0);
  // Frame 3 is 1 frame before the cut at 4: weight of the next stretch 0.5 (1 - 1/1.5) = 1/6, read
  // at 30 + (3 - 4) * 0.5 = 29.5, in the reference's own lead-in to that stretch.
  EXPECT_DOUBLE_EQ(s[3].a, 16.0);
  EXPECT_DOUBLE_EQ(s[3].b, 29.5);
  EXPECT_NEAR(s[3].w, 1.0 / 6.0, 1e-12);
  EXPECT_DOUBLE_EQ(s[4].a, 30.0);  // at the cut: half and half
  EXPECT_DOUBLE_EQ(s[4].b, 18.0);  // the first stretch read on past its last frame (17)
  EXPECT_DOUBLE_EQ(s[4].w, 0.5);
  // Read on, the partner stays inside its clip: a stretch at the clip's first frame holds it.
  const std::vector<FaceCandidate> at_start = {{10.0, 18.0, 0, 0.0}, {0.0, 4.0, 0, 0.0}};
  EXPECT_DOUBLE_EQ(face_sources(r, units, at_start, 12, 1.5)[3].b, 0.0);
  EXPECT_DOUBLE_EQ(s[6].a, 31.0);
  EXPECT_DOUBLE_EQ(s[6].w, 0.0);
  EXPECT_DOUBLE_EQ(s[10].a, 33.0);
  EXPECT_DOUBLE_EQ(s[11].a, 33.0);  // 33.5, held at the stretch's last frame
  // No cut when the second stretch goes on where the first ends.
  const std::vector<FaceCandidate> on = {{10.0, 18.0, 0, 0.0}, {18.0, 22.0, 0, 0.0}};
  for (const FaceSource& x : face_sources(r, units, on, 12, 1.5)) EXPECT_DOUBLE_EQ(x.w, 0.0);
}

}  // namespace
}  // namespace gmg
