// Gathering a frame's candidates (graph/candidate_gathering.h): the radius after every member is
// the one the definition gives (the k-th nearest so far plus its float error, once k are in), and
// the members resolved are the k nearest, however the members arrive and however many.
#include <algorithm>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "graph/candidate_gathering.h"
#include "graph/pose_space.h"

namespace gmg {
namespace {

// A pose space of n frames (small random features): Gathered reads its float error, and its
// distance in double for members tied with the k-th. (The space keeps a reference to its
// parameters: they live beside it.)
PoseFeatures small_features(int n) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  PoseFeatures f;
  f.positions.resize(6, n);
  f.velocities.resize(6, n);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 6; ++d) f.positions(d, i) = normal(rng);
  f.velocities.col(0) = f.positions.col(1) - f.positions.col(0);
  for (int i = 1; i < n; ++i) f.velocities.col(i) = f.positions.col(i) - f.positions.col(i - 1);
  return f;
}

struct SmallSpace {
  GraphParams params;
  neighbours::PoseSpace space{small_features(400), params};
};

// Distances 1.0, 1.5, 2.0, ... for members 0, 1, 2, ...: half a unit apart, far beyond the float
// error of a distance of a few hundred, so that the k nearest are never tied.
float distance_of(int r) { return 1.0f + 0.5f * static_cast<float>(r); }

// Adds the members in `arrival` order and checks the radius after each against the definition:
// the starting radius until k members are in, then the smaller of it and the k-th smallest
// distance so far plus its error. Returns what resolve gives, and the radius after each member in
// out_radii when given.
std::vector<Candidate> gather(const neighbours::PoseSpace& space, std::size_t k, float start,
                              const std::vector<int>& arrival, std::vector<float>* out_radii = nullptr) {
  std::vector<Candidate> items;
  std::vector<float> kth;
  std::vector<std::pair<double, int>> ties;
  neighbours::Gathered g(space, k, start, items, kth, ties);
  std::vector<float> so_far;
  for (const int r : arrival) {
    g.add(distance_of(r), r);
    so_far.push_back(distance_of(r));
    float want = start;
    if (k > 0 && so_far.size() >= k) {
      std::vector<float> sorted = so_far;
      std::sort(sorted.begin(), sorted.end());
      want = std::min(start, neighbours::kth_radius(space, sorted[k - 1]));
    }
    EXPECT_EQ(g.radius(), want) << "after " << so_far.size() << " members";
    if (out_radii) out_radii->push_back(g.radius());
  }
  std::vector<Candidate> out;
  g.resolve(0, out);
  return out;
}

std::vector<int> rs_of(const std::vector<Candidate>& c) {
  std::vector<int> rs(c.size());
  std::transform(c.begin(), c.end(), rs.begin(), [](const Candidate& x) { return x.r; });
  return rs;
}

TEST(CandidateGathering, NearestFirstKeepsTheStartingRadiusUntilKAreIn) {
  const SmallSpace small;
  const neighbours::PoseSpace& space = small.space;
  ASSERT_LT(space.error(distance_of(399)) * 4.1f, 0.5f) << "members must not be tied";
  std::vector<int> arrival(300);
  std::iota(arrival.begin(), arrival.end(), 0);  // as a best-first walk finds them
  const std::vector<Candidate> out = gather(space, 128, 1000.0f, arrival);
  std::vector<int> want(128);
  std::iota(want.begin(), want.end(), 0);
  EXPECT_EQ(rs_of(out), want);
  for (const Candidate& c : out) EXPECT_EQ(c.d, distance_of(c.r));
}

TEST(CandidateGathering, AnyOrderGivesTheKNearest) {
  const SmallSpace small;
  const neighbours::PoseSpace& space = small.space;
  std::mt19937 rng(9);
  for (const std::size_t count : {std::size_t{50}, std::size_t{128}, std::size_t{129}, std::size_t{400}}) {
    std::vector<int> arrival(count);
    std::iota(arrival.begin(), arrival.end(), 0);
    std::shuffle(arrival.begin(), arrival.end(), rng);
    const std::vector<Candidate> out = gather(space, 128, 1000.0f, arrival);
    // Members 0 .. min(count, 128) - 1 are the nearest; resolve gives them by ascending r.
    std::vector<int> want(std::min<std::size_t>(count, 128));
    std::iota(want.begin(), want.end(), 0);
    EXPECT_EQ(rs_of(out), want) << count << " members";
  }
}

TEST(CandidateGathering, FarthestFirstShrinksTheRadiusAtEveryMemberAfterK) {
  // The worst order for a heap of the k nearest: every member after the k-th replaces its top.
  const SmallSpace small;
  const neighbours::PoseSpace& space = small.space;
  std::vector<int> arrival(400);
  std::iota(arrival.rbegin(), arrival.rend(), 0);  // 399, 398, ..., 0
  std::vector<float> radii;
  const std::vector<Candidate> out = gather(space, 16, 1000.0f, arrival, &radii);
  ASSERT_EQ(radii.size(), arrival.size());
  for (std::size_t i = 0; i + 1 < 16; ++i) EXPECT_EQ(radii[i], 1000.0f) << i;
  for (std::size_t i = 16; i < radii.size(); ++i) EXPECT_LT(radii[i], radii[i - 1]) << i;
  std::vector<int> want(16);
  std::iota(want.begin(), want.end(), 0);
  EXPECT_EQ(rs_of(out), want);
}

TEST(CandidateGathering, MembersTiedWithTheKthAreRankedByTheirDistanceInDouble) {
  // Ten members clearly nearer than the rest, then a hundred at one float distance: the sixteen
  // are the ten and the six of the hundred nearest to frame 0 in double (by frame when equal).
  const SmallSpace small;
  const neighbours::PoseSpace& space = small.space;
  std::vector<Candidate> items;
  std::vector<float> kth;
  std::vector<std::pair<double, int>> ties;
  neighbours::Gathered g(space, 16, 1000.0f, items, kth, ties);
  std::vector<int> tied;
  for (int r = 111; r >= 2; --r) {  // the far ones first, in descending frame order
    const bool sure = r < 12;
    g.add(sure ? 1.0f : 5.0f, r);
    if (!sure) tied.push_back(r);
  }
  std::sort(tied.begin(), tied.end(), [&](int a, int b) {
    const double da = space.exact(0, a), db = space.exact(0, b);
    return da < db || (da == db && a < b);
  });
  std::vector<int> want = {2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  want.insert(want.end(), tied.begin(), tied.begin() + 6);
  std::sort(want.begin(), want.end());
  std::vector<Candidate> out;
  g.resolve(0, out);
  EXPECT_EQ(rs_of(out), want);
}

TEST(CandidateGathering, NoBoundKeepsEveryMemberWithinTheRadius) {
  const SmallSpace small;
  const neighbours::PoseSpace& space = small.space;
  std::vector<int> arrival = {7, 3, 250, 0, 90};
  // A radius of 50 takes distances up to 50: members 0 .. 98, so not 250.
  const std::vector<Candidate> out = gather(space, 0, 50.0f, arrival);
  EXPECT_EQ(rs_of(out), (std::vector<int>{0, 3, 7, 90}));
}

}  // namespace
}  // namespace gmg
