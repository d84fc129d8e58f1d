// The candidate search's pose space (graph/pose_space.h) and the feature store under it
// (graph/features.h): single-precision distances summed in one fixed order whatever the vector
// width, within their stated error of d, projections that bound d from below, and distances in
// double that are pose_distance's bit for bit.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "graph/pose_space.h"

namespace gmg {
namespace {

// Features of n frames in `dims` dimensions, random but correlated across frames, in clips that
// start at `starts` (each a clip's velocities as pose_features gives them).
PoseFeatures random_features(int dims, int n, unsigned seed, const std::vector<int>& starts = {0}) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  PoseFeatures f;
  f.positions.resize(dims, n);
  f.velocities.resize(dims, n);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < dims; ++d) f.positions(d, i) = 10.0 * std::sin(0.01 * i * (d + 1)) + normal(rng);
  for (int i = 0; i < n; ++i) {
    const bool start = std::find(starts.begin(), starts.end(), i) != starts.end();
    f.velocities.col(i) =
        start ? f.positions.col(i + 1) - f.positions.col(i) : f.positions.col(i) - f.positions.col(i - 1);
  }
  return f;
}

// NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): the bits are what is compared
bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The order graph/float_lanes.h promises, written out one float at a time: sixteen running sums,
// dimension j into sum j mod 16 in ascending j, then ((s0 + s1) + (s2 + s3)) + ... pairwise.
float fixed_order_norm(const std::vector<float>& x, const std::vector<float>& y) {
  float s[16] = {};
  for (std::size_t j = 0; j < x.size(); ++j) s[j % 16] += (x[j] - y[j]) * (x[j] - y[j]);
  auto sum8 = [](const float* v) { return ((v[0] + v[1]) + (v[2] + v[3])) + ((v[4] + v[5]) + (v[6] + v[7])); };
  return std::sqrt(sum8(s) + sum8(s + 8));
}

// approx(l, r) as the fixed order gives it, for features of 45 dimensions (padded to 48) in clips
// starting at `starts`: positions centred on the mean and rounded to float; velocities the
// difference of two of them, the next frame's at a clip start.
float expected_approx(const PoseFeatures& f, const std::vector<int>& starts, float lp, float lv, int l, int r) {
  const int dims = static_cast<int>(f.positions.rows());
  const std::size_t padded = (static_cast<std::size_t>(dims) + 15) / 16 * 16;
  const Eigen::VectorXd mean = f.positions.rowwise().mean();
  auto position = [&](int i) {
    std::vector<float> out(padded, 0.0f);
    for (int d = 0; d < dims; ++d) out[static_cast<std::size_t>(d)] = static_cast<float>(f.positions(d, i) - mean(d));
    return out;
  };
  auto velocity = [&](int i) {
    const bool start = std::find(starts.begin(), starts.end(), i) != starts.end();
    const std::vector<float> a = position(start ? i + 1 : i), b = position(start ? i : i - 1);
    std::vector<float> out(padded);
    for (std::size_t d = 0; d < out.size(); ++d) out[d] = a[d] - b[d];
    return out;
  };
  return lp * fixed_order_norm(position(l), position(r)) + lv * fixed_order_norm(velocity(l), velocity(r));
}

TEST(PoseSpace, FloatDistanceIsSummedInTheFixedOrder) {
  const int dims = 45, n = 50;  // 45 values padded to 48: three rounds of the sixteen sums
  const PoseFeatures f = random_features(dims, n, 3, {0, 20});  // two clips
  GraphParams p;
  p.lambda_pos = 1.0;
  p.lambda_vel = 2.0;
  neighbours::PoseSpace space(f, p);
  for (int l = 0; l < n; l += 3)
    for (int r = 0; r < n; r += 5)
      EXPECT_TRUE(same_bits(space.approx(l, r), expected_approx(f, {0, 20}, 1.0f, 2.0f, l, r))) << l << " " << r;
}

// A search tree's order puts frame order[s] in slot s. Within the row budget the positions and
// velocities move to slot order too (a leaf's rows side by side); over it they stay in frame order.
// Both give the fixed order's distance, bit for bit, by frame and by slot.
TEST(PoseSpace, SlotOrderRowsGiveTheSameDistanceBitForBit) {
  const int dims = 45, n = 50;
  const std::vector<int> starts = {0, 17, 40};
  const PoseFeatures f = random_features(dims, n, 11, starts);
  GraphParams p;
  p.lambda_pos = 1.5;
  p.lambda_vel = 0.5;
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int s = 0; s < n; ++s) order[static_cast<std::size_t>(s)] = (s * 7 + 3) % n;  // 7 is prime to 50
  neighbours::PoseSpace in_slots(f, p), in_frames(f, p);
  in_slots.set_order(order);
  in_frames.set_order(order, 0);
  ASSERT_TRUE(in_slots.ordered_rows());
  ASSERT_FALSE(in_frames.ordered_rows());
  for (int l = 0; l < n; l += 2)
    for (int r = 0; r < n; r += 3) {
      const float expected = expected_approx(f, starts, 1.5f, 0.5f, l, r);
      EXPECT_EQ(in_slots.slot(l), in_frames.slot(l));
      EXPECT_TRUE(same_bits(in_slots.approx_slots(in_slots.slot(l), in_slots.slot(r)), expected)) << l << " " << r;
      EXPECT_TRUE(same_bits(in_slots.approx(l, r), expected)) << l << " " << r;
      EXPECT_TRUE(same_bits(in_frames.approx(l, r), expected)) << l << " " << r;
    }
  // Frame order[s] is in slot s.
  for (int s = 0; s < n; ++s) EXPECT_EQ(in_slots.slot(order[static_cast<std::size_t>(s)]), s);
}

TEST(FeatureStore, DistanceIsPoseDistanceBitForBitAcrossClips) {
  const PoseFeatures f = random_features(30, 60, 7, {0, 25, 26 + 10});
  GraphParams p;
  p.lambda_vel = 1.5;
  const auto store = FeatureStore::of(f);
  EXPECT_EQ(store->frame_count(), 60);
  EXPECT_TRUE(store->clip_start(25));
  EXPECT_FALSE(store->clip_start(26));
  for (int l = 0; l < 60; ++l)
    for (int r = 0; r < 60; r += 3) {
      const double expected = pose_distance(f, l, r, p);
      const double got = store->distance(l, r, p);
      // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): the bits are what is compared
      EXPECT_EQ(std::memcmp(&got, &expected, sizeof got), 0) << l << " " << r;
    }
}

// Clips of 63, 2, 64, 3, 60, 129 and 2 frames: starts at the last bit of a 64-frame word, at the
// first, and inside words, in clips shorter and longer than a word.
TEST(FeatureStore, KnowsEveryClipStartAndNoOtherFrame) {
  const std::vector<int> lengths = {63, 2, 64, 3, 60, 129, 2};
  FeatureStore store(4);
  std::vector<int> starts;
  int frames = 0;
  for (std::size_t c = 0; c < lengths.size(); ++c) {
    starts.push_back(frames);
    store.add_clip(random_features(4, lengths[c], static_cast<unsigned>(c)));
    frames += lengths[c];
  }
  store.finish();
  ASSERT_EQ(store.frame_count(), 323);
  // 0, 63, 65, 129, 132, 192, 321: frames 63 and 192 are the last bit of a word and the first.
  EXPECT_EQ(starts, (std::vector<int>{0, 63, 65, 129, 132, 192, 321}));
  for (int f = 0; f < frames; ++f) {
    const bool start = std::find(starts.begin(), starts.end(), f) != starts.end();
    EXPECT_EQ(store.clip_start(f), start) << f;
    EXPECT_EQ(store.velocity_frames(f), start ? std::pair(f + 1, f) : std::pair(f, f - 1)) << f;
  }
}

TEST(FeatureStore, RefusesVelocitiesThatAreNotPositionDifferences) {
  PoseFeatures f = random_features(6, 10, 1);
  f.velocities(2, 4) += 1e-9;
  EXPECT_THROW(FeatureStore::of(f), Error);
}

TEST(FeatureStore, SpilledPositionsGiveTheSameDistances) {
  const PoseFeatures f = random_features(12, 40, 9, {0, 15});
  GraphParams p;
  const auto memory = FeatureStore::of(f);
  FeatureStore spilled(12, ::testing::TempDir(), 1000);  // the second clip crosses 1000 bytes
  PoseFeatures a, b;
  a.positions = f.positions.leftCols(15);
  a.velocities = f.velocities.leftCols(15);
  b.positions = f.positions.rightCols(25);
  b.velocities = f.velocities.rightCols(25);
  spilled.add_clip(a);
  spilled.add_clip(b);
  spilled.finish();
  EXPECT_TRUE(spilled.spilled());
  EXPECT_FALSE(memory->spilled());
  for (int l = 0; l < 40; ++l)
    for (int r = 0; r < 40; ++r) EXPECT_EQ(spilled.distance(l, r, p), memory->distance(l, r, p));
}

TEST(PoseSpace, FloatDistanceWithinItsErrorAndBoundedBelowByTheProjections) {
  const PoseFeatures f = random_features(75, 400, 5, {0, 150});
  GraphParams p;
  neighbours::PoseSpace space(f, p);
  EXPECT_LE(space.position_dims(), 8);
  EXPECT_LE(space.velocity_dims(), 8);
  for (int l = 0; l < 400; l += 13)
    for (int r = 0; r < 400; r += 11) {
      const double d = pose_distance(f, l, r, p);
      EXPECT_LE(std::abs(space.approx(l, r) - d), space.error(static_cast<float>(d))) << l << " " << r;
      EXPECT_LE(space.lower_bound_slots(l, r), space.approx(l, r) + space.error(static_cast<float>(d)));
    }
}

}  // namespace
}  // namespace gmg
