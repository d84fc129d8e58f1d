// Anchors (search/anchors.h): rests found from a pause track made by hand, and subsequence lists
// cut at rests and pins, with every expected piece worked out here.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/core/error.h"
#include "search/anchors.h"

namespace gmg {
namespace {

std::vector<float> pauses(int total, const std::vector<std::pair<int, int>>& runs, float value = 1.0f) {
  std::vector<float> p(static_cast<std::size_t>(total), 0.0f);
  for (const auto& [from, to] : runs)
    for (int f = from; f < to; ++f) p[static_cast<std::size_t>(f)] = value;
  return p;
}

void expect_anchor(const Anchor& a, int start, int length, int lead) {
  EXPECT_EQ(a.start, start);
  EXPECT_EQ(a.length, length);
  EXPECT_EQ(a.lead, lead);
  EXPECT_EQ(a.kind, Fixed::Rest);
  EXPECT_EQ(a.source, -1);
}

TEST(RestAnchors, LongPausesBecomeRestsWithLeadAndHold) {
  // 10 fps, rest_min_s 0.5: pauses of 5 frames or more. Pauses [20, 30), [50, 54) (too short), [70, 90).
  const std::vector<float> p = pauses(100, {{20, 30}, {50, 54}, {70, 90}});
  const std::vector<Anchor> r = rest_anchors(p, 10.0, 0.5, 8, 3);
  ASSERT_EQ(r.size(), 2u);
  expect_anchor(r[0], 17, 3 + 8, 3);  // 3 lead frames, then still for hold = 8 of the pause's 10
  expect_anchor(r[1], 67, 3 + 8, 3);
}

TEST(RestAnchors, AShortPauseIsHeldWhole) {
  const std::vector<Anchor> r = rest_anchors(pauses(100, {{40, 46}}), 10.0, 0.5, 20, 4);
  ASSERT_EQ(r.size(), 1u);
  expect_anchor(r[0], 36, 4 + 6, 4);
}

TEST(RestAnchors, ExactlyRestMinIsEnoughOneLessIsNot) {
  EXPECT_EQ(rest_anchors(pauses(100, {{40, 45}}), 10.0, 0.5, 20, 0).size(), 1u);
  EXPECT_TRUE(rest_anchors(pauses(100, {{40, 44}}), 10.0, 0.5, 20, 0).empty());
}

TEST(RestAnchors, PauseThresholdIsOneHalf) {
  EXPECT_EQ(rest_anchors(pauses(100, {{40, 50}}, 0.5f), 10.0, 0.5, 20, 0).size(), 1u);
  EXPECT_TRUE(rest_anchors(pauses(100, {{40, 50}}, 0.49f), 10.0, 0.5, 20, 0).empty());
}

TEST(RestAnchors, LeadNeverBeforeTheOutputOrThePreviousRest) {
  // Pauses [2, 12) and [24, 40), lead 15, hold 10: the first rest may lead only 2 frames (from the
  // output's start) and ends at 12; the second's lead would reach back to 9, so it starts at 12.
  const std::vector<Anchor> r = rest_anchors(pauses(60, {{2, 12}, {24, 40}}), 10.0, 0.5, 10, 15);
  ASSERT_EQ(r.size(), 2u);
  expect_anchor(r[0], 0, 2 + 10, 2);
  expect_anchor(r[1], 12, 12 + 10, 12);
}

TEST(RestAnchors, NoHoldNoRests) {
  EXPECT_TRUE(rest_anchors(pauses(100, {{20, 60}}), 10.0, 0.5, 0, 3).empty());
  EXPECT_TRUE(rest_anchors({}, 10.0, 0.5, 5, 3).empty());
}

Subsequence sub(int start, int length, Termination kind = Termination::Rhythm, const std::string& keyword = "") {
  Subsequence s;
  s.start = start;
  s.length = length;
  s.kind = kind;
  s.keyword = keyword;
  return s;
}

Anchor rest(int start, int length, int lead = 0) { return {start, length, Fixed::Rest, -1, lead}; }
Anchor pin(int start, int length, int source) { return {start, length, Fixed::Pin, source, 0}; }

void expect_covering(const std::vector<Subsequence>& subs, int total) {
  int at = 0;
  for (const Subsequence& s : subs) {
    EXPECT_EQ(s.start, at);
    EXPECT_GE(s.length, 1);
    at = s.start + s.length;
  }
  EXPECT_EQ(at, total);
}

TEST(PlaceAnchors, CutsAtRestsAndPins) {
  const std::vector<Subsequence> subs = {sub(0, 30, Termination::Keyword, "big"), sub(30, 40),
                                         sub(70, 30, Termination::Keyword, "this")};
  const std::vector<Subsequence> out = place_anchors(subs, {rest(20, 15, 2), pin(60, 10, 500)}, 1);
  expect_covering(out, 100);
  ASSERT_EQ(out.size(), 5u);
  // [0, 20): the keyword subsequence cut short by the rest now ends on rhythm.
  EXPECT_EQ(out[0].length, 20);
  EXPECT_EQ(out[0].kind, Termination::Rhythm);
  EXPECT_EQ(out[0].keyword, "");
  EXPECT_EQ(out[0].fixed, Fixed::None);
  // The rest.
  EXPECT_EQ(out[1].start, 20);
  EXPECT_EQ(out[1].fixed, Fixed::Rest);
  EXPECT_EQ(out[1].lead, 2);
  // [35, 60) walks into the pin's first frame.
  EXPECT_EQ(out[2].start, 35);
  EXPECT_EQ(out[2].kind, Termination::Frame);
  EXPECT_EQ(out[2].stop_frame, 500);
  EXPECT_EQ(out[2].fixed, Fixed::None);
  // The pin plays graph frames 500...
  EXPECT_EQ(out[3].fixed, Fixed::Pin);
  EXPECT_EQ(out[3].source, 500);
  EXPECT_EQ(out[3].length, 10);
  // [70, 100) is untouched.
  EXPECT_EQ(out[4].start, 70);
  EXPECT_EQ(out[4].kind, Termination::Keyword);
  EXPECT_EQ(out[4].keyword, "this");
}

TEST(PlaceAnchors, AnchorsAtTheStartAndTheEnd) {
  const std::vector<Subsequence> subs = {sub(0, 50), sub(50, 50, Termination::Keyword, "not")};
  const std::vector<Subsequence> out = place_anchors(subs, {pin(0, 10, 7), rest(90, 10)}, 1);
  expect_covering(out, 100);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0].fixed, Fixed::Pin);  // nothing before it to end on its frame
  EXPECT_EQ(out[0].source, 7);
  EXPECT_EQ(out[1].start, 10);
  EXPECT_EQ(out[1].length, 40);
  EXPECT_EQ(out[1].kind, Termination::Rhythm);
  EXPECT_EQ(out[2].start, 50);
  EXPECT_EQ(out[2].length, 40);
  EXPECT_EQ(out[2].kind, Termination::Rhythm);  // cut short by the rest
  EXPECT_EQ(out[3].fixed, Fixed::Rest);
  EXPECT_EQ(out[3].start, 90);
}

TEST(PlaceAnchors, ShortPiecesJoinTheOneBefore) {
  const std::vector<Subsequence> subs = {sub(0, 30), sub(30, 4, Termination::Keyword, "big"),
                                         sub(34, 66, Termination::Keyword, "this")};
  const std::vector<Subsequence> out = place_anchors(subs, {rest(60, 10)}, 8);
  expect_covering(out, 100);
  ASSERT_EQ(out.size(), 4u);
  // The 4-frame piece joins [0, 30), which takes its end and termination.
  EXPECT_EQ(out[0].length, 34);
  EXPECT_EQ(out[0].kind, Termination::Keyword);
  EXPECT_EQ(out[0].keyword, "big");
  EXPECT_EQ(out[1].start, 34);
  EXPECT_EQ(out[1].kind, Termination::Rhythm);
  EXPECT_EQ(out[2].fixed, Fixed::Rest);
  EXPECT_EQ(out[3].start, 70);
  EXPECT_EQ(out[3].keyword, "this");
}

TEST(PlaceAnchors, AShortFirstPieceJoinsTheOneAfter) {
  const std::vector<Subsequence> subs = {sub(0, 22, Termination::Keyword, "big"),
                                         sub(22, 78, Termination::Keyword, "very")};
  const std::vector<Subsequence> out = place_anchors(subs, {rest(10, 10)}, 5);
  expect_covering(out, 100);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[2].start, 20);
  EXPECT_EQ(out[2].length, 80);
  EXPECT_EQ(out[2].keyword, "very");
  EXPECT_EQ(out[2].fixed, Fixed::None);
}

TEST(PlaceAnchors, LengthsSumToTheTotal) {
  std::vector<Subsequence> subs;
  for (int s = 0; s < 300; s += 17) subs.push_back(sub(s, std::min(17, 300 - s)));
  const std::vector<Subsequence> out =
      place_anchors(subs, {rest(5, 20, 3), pin(40, 30, 1000), pin(70, 5, 2000), rest(250, 50)}, 6);
  expect_covering(out, 300);
  int fixed = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i].fixed == Fixed::None) continue;
    ++fixed;
    // Every pin is walked into from a planned piece, when there is one before it.
    if (out[i].fixed == Fixed::Pin && i > 0 && out[i - 1].fixed == Fixed::None) {
      EXPECT_EQ(out[i - 1].kind, Termination::Frame);
      EXPECT_EQ(out[i - 1].stop_frame, out[i].source);
    }
  }
  EXPECT_EQ(fixed, 4);
}

TEST(PlaceAnchors, NoAnchorsChangesNothing) {
  const std::vector<Subsequence> subs = {sub(0, 30, Termination::Keyword, "big"), sub(30, 70)};
  const std::vector<Subsequence> out = place_anchors(subs, {}, 10);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].keyword, "big");
  EXPECT_EQ(out[1].length, 70);
}

TEST(PlaceAnchors, BadAnchorsThrow) {
  const std::vector<Subsequence> subs = {sub(0, 100)};
  const std::vector<std::vector<Anchor>> bad = {{rest(10, 20), rest(25, 5)},  // overlapping
                                                {rest(50, 5), rest(10, 5)},   // unsorted
                                                {rest(95, 10)},               // past the output's end
                                                {rest(-1, 5)},                // before its start
                                                {rest(10, 0)},                // empty
                                                {{10, 5, Fixed::None, -1, 0}}};
  for (const std::vector<Anchor>& anchors : bad) EXPECT_THROW(place_anchors(subs, anchors, 1), Error);
}

}  // namespace
}  // namespace gmg
