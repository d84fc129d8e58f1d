// Segmentation of the test speech into subsequences.
#include <gtest/gtest.h>

#include "search/segmentation.h"

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

}  // namespace
}  // namespace gmg
