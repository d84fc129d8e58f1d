// The candidate search's pose space (graph/pose_space.h): single-precision distances summed in one
// fixed order whatever the vector width, within their stated error of d, and projections that
// bound d from below.
#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "graph/pose_space.h"

namespace gmg {
namespace {

// Features of n frames in `dims` dimensions, random but correlated across frames.
PoseFeatures random_features(int dims, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  PoseFeatures f;
  f.positions.resize(dims, n);
  f.velocities.resize(dims, n);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < dims; ++d) {
      f.positions(d, i) = 10.0 * std::sin(0.01 * i * (d + 1)) + normal(rng);
      f.velocities(d, i) = 0.3 * normal(rng);
    }
  return f;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The order graph/float_lanes.h promises, written out one float at a time: sixteen running sums,
// dimension j into sum j mod 16 in ascending j, then ((s0 + s1) + (s2 + s3)) + ... pairwise.
float fixed_order_norm(const std::vector<float>& x, const std::vector<float>& y) {
  float s[16] = {};
  for (std::size_t j = 0; j < x.size(); ++j) s[j % 16] += (x[j] - y[j]) * (x[j] - y[j]);
  auto sum8 = [](const float* v) { return ((v[0] + v[1]) + (v[2] + v[3])) + ((v[4] + v[5]) + (v[6] + v[7])); };
  return std::sqrt(sum8(s) + sum8(s + 8));
}

TEST(PoseSpace, FloatDistanceIsSummedInTheFixedOrder) {
  const int dims = 45, n = 50;  // 45 values padded to 48: three rounds of the sixteen sums
  const PoseFeatures f = random_features(dims, n, 3);
  GraphParams p;
  p.lambda_pos = 1.0;
  p.lambda_vel = 2.0;
  neighbours::PoseSpace space(f, p);
  space.set_order({});
  const Eigen::VectorXd mp = f.positions.rowwise().mean(), mv = f.velocities.rowwise().mean();
  auto centred = [&](const Eigen::MatrixXd& m, const Eigen::VectorXd& mean, int i) {
    std::vector<float> out(48, 0.0f);
    for (int d = 0; d < dims; ++d) out[static_cast<std::size_t>(d)] = static_cast<float>(m(d, i) - mean(d));
    return out;
  };
  for (int l = 0; l < n; l += 7)
    for (int r = 0; r < n; r += 5) {
      const float expected = 1.0f * fixed_order_norm(centred(f.positions, mp, l), centred(f.positions, mp, r)) +
                             2.0f * fixed_order_norm(centred(f.velocities, mv, l), centred(f.velocities, mv, r));
      EXPECT_TRUE(same_bits(space.approx(l, r), expected)) << l << " " << r;
    }
}

TEST(PoseSpace, FloatDistanceWithinItsErrorAndBoundedBelowByTheProjections) {
  const PoseFeatures f = random_features(75, 400, 5);
  GraphParams p;
  neighbours::PoseSpace space(f, p);
  space.set_order({});
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
